# `animate` replays a session's shape strokes (issue 13): a session with shape strokes, a pose
# model and keyframes, but no `face`, animates the face its shape strokes build (as `sketch`
# replays them, the rigid parts following the skin), not the pose model's mean face. The .glb is
# read by three.js in headless chromium: at 0 s (a keyframe before any pose stroke) vertices at the
# back of the head, which the mapping leaves where they are, are those of `sketch`'s face (within
# 0.01 mm) and not those of the mean face (0.3 to 1.3 mm away). (The mouth's are not compared: the
# mapping of a zero FP pose moves the lips of this small pose model by up to 2.3 mm.) Run by ctest
# with -DFACESKETCH=<exe> -DSAMPLE=<pose_sample> -DNODE=<node> -DTOOLS=<tools/gltf> -DWORK=<dir>.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

include(${CMAKE_CURRENT_LIST_DIR}/common.cmake)

# The pose model and pose actions of pose_sample (synthetic low topology), a face model of the
# same topology, and shape strokes tracing one of its test faces.
run_command(${SAMPLE} ${WORK})
run(synth -o ${WORK}/faces --identities 40 --seed 3)
run(train ${WORK}/faces -o ${WORK}/faces.model -k 7 --folds 3 --latent-dim 6 --cleanup-dim 12 --correlation-dim 10 --restarts 1 -q)
run(strokes simulate ${WORK}/faces --sample face_0039 --view front --noise 1 -o ${WORK}/shape.json)
run(sketch ${WORK}/faces.model ${WORK}/faces --session ${WORK}/shape.json -o ${WORK}/sketched.obj --similar 0)

# One session: the shape strokes, then pose_sample's keyframes and pose strokes.
file(READ ${WORK}/shape.json session)
file(READ ${WORK}/session.json posing)
string(JSON session SET "${session}" version 2)
string(JSON session SET "${session}" poses "\"poses.model\"")
string(JSON shapes LENGTH "${session}" actions)
string(JSON poseCount LENGTH "${posing}" actions)
math(EXPR last "${poseCount} - 1")
foreach(i RANGE ${last})
  string(JSON action GET "${posing}" actions ${i})
  math(EXPR at "${shapes} + ${i}")
  string(JSON session SET "${session}" actions ${at} "${action}")
endforeach()
file(WRITE ${WORK}/combined.json "${session}")
# The pose model's mean face, unposed: a session with no shape strokes and no face.
file(WRITE ${WORK}/mean.json "{\"format\": \"facesketch-session\", \"version\": 2, \"poses\": \"poses.model\", \"actions\": [{\"type\": \"pose-clear\"}]}")
run(pose ${WORK}/poses.model --session ${WORK}/mean.json -o ${WORK}/mean.obj)

run(animate ${WORK}/combined.json -o ${WORK}/anim.glb --fps 10)
if(NOT out MATCHES "# ${shapes} shape strokes replayed \\(${shapes} applied, 0 refused\\): the face to pose")
  message(FATAL_ERROR "animate did not replay the ${shapes} shape strokes: ${out}")
endif()
if(NOT out MATCHES "3 keyframes, 0 to 2 s, 21 frames at 10 fps")
  message(FATAL_ERROR "animate printed: ${out}")
endif()

# expected-NAME.json: skin vertices 0, 25 and 50 of NAME.obj at 0 s, for tools/gltf/three-check.mjs.
function(expect_from name)
  file(STRINGS ${WORK}/${name}.obj vertices REGEX "^v ")
  set(checks "")
  foreach(v 0 25 50)
    list(GET vertices ${v} line)
    string(REPLACE " " ";" xyz "${line}")
    list(GET xyz 1 x)
    list(GET xyz 2 y)
    list(GET xyz 3 z)
    list(APPEND checks "{\"time\": 0, \"node\": \"face\", \"vertex\": ${v}, \"position\": [${x}, ${y}, ${z}]}")
  endforeach()
  list(JOIN checks ", " checks)
  file(WRITE ${WORK}/expected-${name}.json "{\"toleranceMm\": 0.01, \"mmPerUnit\": 1000, \"checks\": [${checks}]}")
endfunction()
expect_from(sketched)
expect_from(mean)
run_command(${NODE} ${TOOLS}/three-check.mjs ${WORK}/anim.glb ${WORK}/expected-sketched.json)
execute_process(COMMAND ${NODE} ${TOOLS}/three-check.mjs ${WORK}/anim.glb ${WORK}/expected-mean.json RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "the animation's first frame is also the mean face: ${out} ${err}")
endif()

# A session's `face` still wins over its shape strokes.
string(JSON named SET "${session}" face "\"face.ply\"")
file(WRITE ${WORK}/named.json "${named}")
run(animate ${WORK}/named.json -o ${WORK}/named.glb --fps 10)
if(out MATCHES "shape strokes replayed")
  message(FATAL_ERROR "animate replayed shape strokes although the session names its face: ${out}")
endif()

# Posing end to end (issue 13): `pose` replays a session's pose strokes and prints the FPs they
# found; `animate` writes PNG frames and a .glb, which the Khronos validator (0 errors, 0
# warnings) and three.js in headless chromium (vertices within 0.01 mm of FaceSketch's frames)
# read; bad sessions fail with exit code 1 naming what is wrong, writing nothing. Run by ctest
# with -DFACESKETCH=<exe> -DSAMPLE=<pose_sample> -DNODE=<node> -DTOOLS=<tools/gltf> -DWORK=<dir>.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

include(${CMAKE_CURRENT_LIST_DIR}/common.cmake)

run_command(${SAMPLE} ${WORK})

# pose: the open smile's lip strokes are read as lip FPs (the session's last pose is the pucker's
# upper lip, after a clear).
run(pose ${WORK}/poses.model --face ${WORK}/face.ply --session ${WORK}/session.json -o ${WORK}/posed.ply)
foreach(fp "8.1" "8.3" "8.4")
  if(NOT out MATCHES "FP ${fp}: stroke 0 \\(upper_lip\\)")
    message(FATAL_ERROR "pose did not print FP ${fp} on the upper lip: ${out}")
  endif()
endforeach()
if(NOT EXISTS ${WORK}/posed.ply)
  message(FATAL_ERROR "pose wrote no mesh")
endif()

# animate: a .glb and PNG frames at 10 fps over 0-2 s (21 frames).
run(animate ${WORK}/session.json -o ${WORK}/anim.glb --fps 10)
if(NOT out MATCHES "3 keyframes, 0 to 2 s, 21 frames at 10 fps")
  message(FATAL_ERROR "animate printed: ${out}")
endif()
run_command(${NODE} ${TOOLS}/validate.mjs ${WORK}/anim.glb)
if(NOT out MATCHES "0 errors, 0 warnings")
  message(FATAL_ERROR "the validator said: ${out}")
endif()
run_command(${NODE} ${TOOLS}/three-check.mjs ${WORK}/anim.glb ${WORK}/expected.json)
run(animate ${WORK}/session.json -o ${WORK}/frames --fps 10 --size 64)
file(GLOB frames ${WORK}/frames/frame_*.png)
list(LENGTH frames count)
if(NOT count EQUAL 21)
  message(FATAL_ERROR "animate wrote ${count} PNG frames, expected 21")
endif()

# Bad input: one keyframe, a stroke that hits no cluster, equal keyframe times, another topology.
file(READ ${WORK}/session.json session)
string(JSON last LENGTH "${session}" actions)
math(EXPR last "${last} - 1")
string(JSON one REMOVE "${session}" actions ${last})
string(JSON one REMOVE "${one}" actions 3)
file(WRITE ${WORK}/one.json "${one}")
expect_failure("timeline: 1 keyframe\\(s\\), a timeline needs at least 2" animate ${WORK}/one.json -o ${WORK}/one.glb)
string(JSON same SET "${session}" actions ${last} time "1.0")
file(WRITE ${WORK}/same.json "${same}")
expect_failure("same.json: actions\\[${last}\\].time: 1 s is also the time of the keyframe at actions\\[3\\]" animate ${WORK}/same.json -o ${WORK}/same.glb)
string(JSON off SET "${session}" actions 1 stroke points 0 y "2.0")
string(JSON count LENGTH "${off}" actions 1 stroke points)
math(EXPR count "${count} - 1")
foreach(i RANGE ${count})
  string(JSON off SET "${off}" actions 1 stroke points ${i} y "2.0")
endforeach()
file(WRITE ${WORK}/off.json "${off}")
expect_failure("actions\\[1\\] \\(pose-stroke\\): pose stroke 0 hits no feature point cluster" pose ${WORK}/poses.model --face ${WORK}/face.ply --session ${WORK}/off.json -o ${WORK}/off.ply)
expect_failure("actions\\[1\\] \\(pose-stroke\\): pose stroke 0 hits no feature point cluster" animate ${WORK}/off.json -o ${WORK}/off.glb)
file(WRITE ${WORK}/tiny.obj "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
expect_failure("the face to pose: 3 vertices, the pose model was trained on a topology of" pose ${WORK}/poses.model --face ${WORK}/tiny.obj --session ${WORK}/session.json -o ${WORK}/tiny.ply)
foreach(f one.glb same.glb off.ply off.glb tiny.ply)
  if(EXISTS ${WORK}/${f})
    message(FATAL_ERROR "${f} was written despite bad input")
  endif()
endforeach()

# The posing statistics end to end on a small posed synthetic set: train-poses writes a pose model,
# eval poses writes its records, and bad input (a dataset without poses, a model file that is not
# a pose model) fails with exit code 1 naming what is wrong, leaving no output behind. Run by ctest
# with -DFACESKETCH=<exe> -DWORK=<dir>.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

include(${CMAKE_CURRENT_LIST_DIR}/common.cmake)

# 14 identities with poses: 10 train, 3 contour, 1 test.
run(synth -o ${WORK}/posed --identities 14 --poses --seed 4)
run(train-poses ${WORK}/posed -o ${WORK}/posed.poses --components 1,3 --latent-dims 4)
if(NOT out MATCHES "trained on 10 identities x 36 poses" OR NOT out MATCHES "K chosen on 3 contour identities")
  message(FATAL_ERROR "train-poses printed: ${out}")
endif()
run(eval poses ${WORK}/posed.poses ${WORK}/posed --json ${WORK}/poses.json)
file(READ ${WORK}/poses.json doc)
string(JSON records LENGTH "${doc}" results)
# (a) completion and its alternative, (b) neutral, statistical mapping and RBF, (c) strokes.
if(NOT records EQUAL 6)
  message(FATAL_ERROR "eval poses wrote ${records} records: ${doc}")
endif()
foreach(i RANGE 5)
  foreach(key task method poses mean_mm ratio)
    string(JSON value GET "${doc}" results ${i} ${key})
  endforeach()
endforeach()
string(JSON task GET "${doc}" results 5 task)
string(JSON method GET "${doc}" results 5 method)
if(NOT task STREQUAL "strokes" OR NOT method STREQUAL "statistical")
  message(FATAL_ERROR "the last record is ${task}/${method}, expected strokes/statistical: ${doc}")
endif()
string(JSON task GET "${doc}" results 3 task)
string(JSON method GET "${doc}" results 4 method)
if(NOT task STREQUAL "mapping" OR NOT method STREQUAL "rbf")
  message(FATAL_ERROR "eval poses records: ${doc}")
endif()

# The fitting run: the 3 contour identities, with another endpoint weight; out-of-range values
# and other identities are refused.
run(eval poses ${WORK}/posed.poses ${WORK}/posed --identities contour --endpoint-weight 2 --json ${WORK}/poses-contour.json)
if(NOT out MATCHES "# 3 contour identities of" OR NOT out MATCHES "strokes +statistical +35 ")
  message(FATAL_ERROR "eval poses --identities contour printed: ${out}")
endif()
# The JSON says which identities and which reading it measured (the default run's too).
file(READ ${WORK}/poses-contour.json contourDoc)
string(JSON role GET "${contourDoc}" role)
string(JSON weight GET "${contourDoc}" endpoint_weight)
string(JSON count GET "${contourDoc}" identities)
string(JSON defaultRole GET "${doc}" role)
if(NOT role STREQUAL "contour" OR NOT weight EQUAL 2 OR NOT count EQUAL 3 OR NOT defaultRole STREQUAL "test")
  message(FATAL_ERROR "eval poses JSON: role ${role}, endpoint weight ${weight}, identities ${count}, default role ${defaultRole}")
endif()
expect_failure("endpoint-weight" eval poses ${WORK}/posed.poses ${WORK}/posed --endpoint-weight 0.5)
expect_failure("identities" eval poses ${WORK}/posed.poses ${WORK}/posed --identities train)

# Bad input: a dataset without poses, a face model given as a pose model; nothing written.
run(synth -o ${WORK}/plain --identities 12 --seed 4)
expect_failure("no identity with poses" train-poses ${WORK}/plain -o ${WORK}/plain.poses)
if(EXISTS ${WORK}/plain.poses)
  message(FATAL_ERROR "train-poses wrote a model after failing")
endif()
file(WRITE ${WORK}/fake.poses "FSKFACE")
expect_failure("not a FaceSketch pose model" eval poses ${WORK}/fake.poses ${WORK}/posed --json ${WORK}/fake.json)
if(EXISTS ${WORK}/fake.json)
  message(FATAL_ERROR "eval poses wrote records after failing")
endif()

# `facesketch register` with a feature point missing must fail with exit code 1, name the scan and
# the point, and write nothing.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND ${FACESKETCH} synth -o ${WORK}/faces --identities 3 --threads 1 RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "synth failed: ${rc}")
endif()
file(WRITE ${WORK}/scan.obj "v 0 0 0\nv 10 0 0\nv 0 10 0\nv 0 0 10\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n")
file(WRITE ${WORK}/scan.points.json "{\"prn\": [0, 0, 10], \"en_l\": [0, 10, 0]}")
execute_process(COMMAND ${FACESKETCH} register ${WORK}/faces ${WORK}/scan.obj --points ${WORK}/scan.points.json -o ${WORK}/out.ply
  RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "expected exit code 1, got ${rc}")
endif()
if(NOT err MATCHES "scan.obj: feature point 'sn' is missing")
  message(FATAL_ERROR "unexpected message: ${err}")
endif()
if(EXISTS ${WORK}/out.ply)
  message(FATAL_ERROR "a mesh was written despite the error")
endif()
# A point that is not a landmark name is refused while reading, naming the file and key.
file(WRITE ${WORK}/bad.points.json "{\"nose\": [0, 0, 10]}")
execute_process(COMMAND ${FACESKETCH} register ${WORK}/faces ${WORK}/scan.obj --points ${WORK}/bad.points.json -o ${WORK}/out.ply
  RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 1 OR NOT err MATCHES "bad.points.json: nose: not a landmark name")
  message(FATAL_ERROR "expected exit code 1 naming the key, got ${rc}: ${err}")
endif()

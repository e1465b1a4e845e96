# `facesketch eval realism` end to end: a synthetic low set against a synthetic high set of the
# same identities (same landmarks, different topology) prints the measures and writes the JSON;
# a reference that is not a dataset and a set with one sample fail naming the folder.
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
run(synth -o ${WORK}/low --identities 6 --resolution low)
run(synth -o ${WORK}/high --identities 6 --resolution high)
run(synth -o ${WORK}/one --identities 1 --resolution low)
run(eval realism ${WORK}/low --reference ${WORK}/high --json ${WORK}/realism.json)
if(NOT out MATCHES "aligned on 32 shared landmarks" OR NOT out MATCHES "\nall +[0-9.]+ +[0-9.]+ +[0-9.]+" OR NOT out MATCHES "data skin")
  message(FATAL_ERROR "eval realism printed no measures: ${out}")
endif()
file(READ ${WORK}/realism.json json)
string(JSON scale GET "${json}" alignment_scale)
string(JSON rms GET "${json}" distances 0 rms_mm)
# The same faces at two resolutions: the same size, and the low mesh's chords within a millimetre or so.
if(scale LESS 0.98 OR scale GREATER 1.02 OR rms GREATER 1.5)
  message(FATAL_ERROR "low vs high of the same faces: scale ${scale}, RMS ${rms} mm")
endif()
expect_failure("nowhere: not a folder" eval realism ${WORK}/low --reference ${WORK}/nowhere)
expect_failure("one: 1 samples" eval realism ${WORK}/one --reference ${WORK}/high)

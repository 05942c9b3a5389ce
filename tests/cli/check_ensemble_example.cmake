# Runs scripts/run_ensemble_examples.sh into OUT_DIR (the main job's ensemble) and fails
# unless it exits 0, prints the summary table, and writes the file and both figures.
file(REMOVE_RECURSE "${OUT_DIR}")
execute_process(COMMAND ${CMAKE_COMMAND} -E env STENGMC_RESULTS_DIR=${OUT_DIR} STENGMC_BINARY=${BINARY}
                        bash "${SOURCE_DIR}/scripts/run_ensemble_examples.sh"
                WORKING_DIRECTORY "${SOURCE_DIR}"
                RESULT_VARIABLE status
                OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "run_ensemble_examples.sh exited ${status}:\n${output}")
endif()
if(NOT output MATCHES "FFT pooled ratio")
  message(FATAL_ERROR "no summary table in the output:\n${output}")
endif()
foreach(product identifiability_quick.h5 identifiability_quick.png identifiability_quick_sweep.png)
  if(NOT EXISTS "${OUT_DIR}/${product}")
    message(FATAL_ERROR "missing ${OUT_DIR}/${product}\n${output}")
  endif()
endforeach()
message(STATUS "the quick ensemble ran; its file and figures exist")

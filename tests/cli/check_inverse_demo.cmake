# Runs scripts/run_inverse_demo.sh into OUT_DIR (the main job's inverse demo) and fails
# unless it exits 0, counts the shipped record's six asperities, and writes the bank, the
# output file and the figure.
file(REMOVE_RECURSE "${OUT_DIR}")
execute_process(COMMAND ${CMAKE_COMMAND} -E env STENGMC_RESULTS_DIR=${OUT_DIR} STENGMC_BINARY=${BINARY}
                        bash "${SOURCE_DIR}/scripts/run_inverse_demo.sh"
                WORKING_DIRECTORY "${SOURCE_DIR}"
                RESULT_VARIABLE status
                OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "run_inverse_demo.sh exited ${status}:\n${output}")
endif()
if(NOT output MATCHES "demo_record.csv +6 +6-6")
  message(FATAL_ERROR "the demo record (six asperities) was not counted 6 with the interval 6-6:\n${output}")
endif()
foreach(product demo_bank.h5 demo_record_inverse.h5 demo_record_inverse.png)
  if(NOT EXISTS "${OUT_DIR}/${product}")
    message(FATAL_ERROR "missing ${OUT_DIR}/${product}\n${output}")
  endif()
endforeach()
message(STATUS "the inverse demo ran; its bank, output and figure exist")

# run_cli(EXPECTED_CODE OUT_VAR ARGS...): runs ${CLI} ARGS, fails the test unless it exits with EXPECTED_CODE,
# and sets OUT_VAR to its stdout followed by its stderr. Included by the tool's end-to-end scripts.
function(run_cli expected_code out_var)
  execute_process(COMMAND ${CLI} ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL expected_code)
    message(FATAL_ERROR "shapestruct ${ARGN}: exit code ${code}, expected ${expected_code}\n${out}\n${err}")
  endif()
  set(${out_var} "${out}${err}" PARENT_SCOPE)
endfunction()

# run_cli(EXPECTED_CODE OUT_VAR ARGS...): runs ${CLI} ARGS, fails the test unless it exits with EXPECTED_CODE,
# and sets OUT_VAR to its stdout followed by its stderr. Included by the tool's end-to-end scripts.
function(run_cli expected_code out_var)
  execute_process(COMMAND ${CLI} ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL expected_code)
    message(FATAL_ERROR "shapestruct ${ARGN}: exit code ${code}, expected ${expected_code}\n${out}\n${err}")
  endif()
  set(${out_var} "${out}${err}" PARENT_SCOPE)
endfunction()

# hash_tree(DIR OUT_VAR SKIP [NAMES_ONLY]): every file under DIR but timings.json/js, one "path sha256" line each,
# sorted. A path matching the regex SKIP is left out; one matching NAMES_ONLY is listed without its hash (the
# pair cache, whose files record their own wall time). report/index.html names its own output folder (the
# explore command line), so DIR is replaced by OUT in it before hashing: folders written apart compare equal.
function(hash_tree dir out_var skip)
  set(names_only "${ARGV3}")
  file(GLOB_RECURSE all RELATIVE ${dir} ${dir}/*)
  list(SORT all)
  set(h "")
  foreach(f IN LISTS all)
    if(f MATCHES "^timings\\.js(on)?$" OR f MATCHES "${skip}")
      continue()
    elseif(names_only AND f MATCHES "${names_only}")
      string(APPEND h "${f}\n")
    elseif(f STREQUAL "report/index.html")
      file(READ ${dir}/${f} text)
      string(REPLACE "${dir}" "OUT" text "${text}")
      string(SHA256 x "${text}")
      string(APPEND h "${f} ${x}\n")
    else()
      file(SHA256 ${dir}/${f} x)
      string(APPEND h "${f} ${x}\n")
    endif()
  endforeach()
  set(${out_var} "${h}" PARENT_SCOPE)
endfunction()

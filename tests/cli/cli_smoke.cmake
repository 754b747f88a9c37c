# End-to-end checks of the shapestruct command-line tool: generate a collection, refuse to overwrite it, inspect
# a generated mesh, and report a malformed file with its name and line. Run by CTest as
#   cmake -DCLI=<path to shapestruct> -DWORK=<scratch folder> -P cli_smoke.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(run_cli expected_code out_var)
  execute_process(COMMAND ${CLI} ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL expected_code)
    message(FATAL_ERROR "shapestruct ${ARGN}: exit code ${code}, expected ${expected_code}\n${out}\n${err}")
  endif()
  set(${out_var} "${out}${err}" PARENT_SCOPE)
endfunction()

run_cli(0 out --help)
foreach(cmd generate inspect)
  if(NOT out MATCHES "  ${cmd} ")
    message(FATAL_ERROR "shapestruct --help does not list '${cmd}':\n${out}")
  endif()
endforeach()

run_cli(0 out generate creatures 3 -o ${WORK}/creatures --seed 7)
file(GLOB meshes ${WORK}/creatures/*.off)
list(LENGTH meshes count)
if(count LESS 3)
  message(FATAL_ERROR "generate creatures 3 wrote ${count} meshes:\n${out}")
endif()
run_cli(0 out generate chairs 4 -o ${WORK}/chairs --seed 7)
file(GLOB segs ${WORK}/chairs/*.seg)
list(LENGTH segs count)
if(NOT count EQUAL 4)
  message(FATAL_ERROR "generate chairs 4 wrote ${count} .seg files")
endif()

# Nothing a user has is overwritten: a second run into the same non-empty folder is refused.
list(GET meshes 0 first_mesh)
file(SHA256 ${first_mesh} before)
run_cli(1 out generate creatures 3 -o ${WORK}/creatures --seed 8)
file(SHA256 ${first_mesh} after)
if(NOT before STREQUAL after)
  message(FATAL_ERROR "generate overwrote ${first_mesh}")
endif()

run_cli(0 out inspect ${first_mesh})
if(NOT out MATCHES "genus")
  message(FATAL_ERROR "inspect printed no genus:\n${out}")
endif()

# A malformed file: exit code 1 and a message naming the file and the line.
file(WRITE ${WORK}/broken.off "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 zero\n3 0 1 2\n")
run_cli(1 out inspect ${WORK}/broken.off)
if(NOT out MATCHES "broken.off:5")
  message(FATAL_ERROR "inspect of a malformed OFF does not name file and line 5:\n${out}")
endif()

# match: a bad option value is a usage error (exit code 2) naming the option, before any mesh is read.
run_cli(2 out match ${first_mesh} ${first_mesh} -o ${WORK}/self.map --pruning bogus)
if(NOT out MATCHES "--pruning must be distances or random")
  message(FATAL_ERROR "match --pruning bogus does not name the option:\n${out}")
endif()

# templates: a bad option value is a usage error (exit code 2) naming the option, before any shape is read.
run_cli(2 out templates ${WORK}/chairs -o ${WORK}/tpl --learn-best 0)
if(NOT out MATCHES "--learn-best >= 1")
  message(FATAL_ERROR "templates --learn-best 0 does not name the option:\n${out}")
endif()

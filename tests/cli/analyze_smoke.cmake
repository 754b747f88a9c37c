# End to end check of `shapestruct analyze` (issue 15): 12 generated chairs plus two bad shapes, every stage,
# the manifest, the report (links, thumbnails not blank), the accuracy, and resuming: a second run redoes
# nothing and changes no file; a run after deleting part of the work (as an interruption would leave it) gives
# the same files byte for byte. Run by CTest as
#   cmake -DCLI=<shapestruct> -DWORK=<scratch folder> -DPYTHON=<python3> -DPNG_CHECK=<png_check.py>
#         [-DCHROMIUM=<chromium>] -P analyze_smoke.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

include(${CMAKE_CURRENT_LIST_DIR}/run_cli.cmake)

run_cli(0 out --help)
if(NOT out MATCHES "  analyze ")
  message("SHAPESTRUCT_SKIP: this shapestruct was built without `analyze` (libpng missing)")
  return()
endif()

set(IN ${WORK}/chairs)
set(OUT ${WORK}/out)
run_cli(0 out generate chairs 12 -o ${IN} --seed 1)
file(WRITE ${IN}/empty.off "OFF\n0 0 0\n")
file(WRITE ${IN}/nan.off "OFF\n3 1 0\n0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n")

run_cli(2 out analyze ${IN} -o ${OUT} --mode sideways)
if(NOT out MATCHES "--mode")
  message(FATAL_ERROR "analyze --mode sideways does not name the option:\n${out}")
endif()

run_cli(0 first analyze ${IN} -o ${OUT} --threads 2)
message(STATUS "first run:\n${first}")
if(NOT first MATCHES "accuracy: [0-9.]+ %")
  message(FATAL_ERROR "analyze printed no accuracy:\n${first}")
endif()
foreach(bad empty.off nan.off)
  if(NOT first MATCHES "skipped ${bad}")
    message(FATAL_ERROR "analyze did not report ${bad} as skipped:\n${first}")
  endif()
endforeach()
if(NOT first MATCHES "extrinsic")
  message(FATAL_ERROR "a collection of polygon soups should be corresponded in extrinsic mode:\n${first}")
endif()

# The manifest: every file and folder it lists exists; it names the mode, the skipped shapes and the accuracy.
file(READ ${OUT}/manifest.json manifest)
string(JSON nfiles LENGTH "${manifest}" files)
if(nfiles LESS 40)
  message(FATAL_ERROR "manifest.json lists only ${nfiles} files")
endif()
math(EXPR last "${nfiles} - 1")
foreach(i RANGE ${last})
  string(JSON path ERROR_VARIABLE no_path GET "${manifest}" files ${i} path)
  if(no_path)
    string(JSON folder GET "${manifest}" files ${i} folder)
    if(NOT IS_DIRECTORY ${OUT}/${folder})
      message(FATAL_ERROR "manifest.json lists the folder ${folder}, which does not exist")
    endif()
  elseif(NOT EXISTS ${OUT}/${path})
    message(FATAL_ERROR "manifest.json lists ${path}, which does not exist")
  endif()
endforeach()
string(JSON mode GET "${manifest}" fuzzy_mode)
string(JSON accuracy GET "${manifest}" accuracy value)
string(JSON nskipped LENGTH "${manifest}" skipped)
if(NOT mode STREQUAL "extrinsic" OR NOT accuracy GREATER 0.5 OR nskipped LESS 2)
  message(FATAL_ERROR "manifest.json: mode ${mode}, accuracy ${accuracy}, ${nskipped} skipped shapes")
endif()
message(STATUS "manifest: ${nfiles} entries, mode ${mode}, accuracy ${accuracy}, ${nskipped} skipped")

# The report: every src / href resolves to a file; one thumbnail and one part-coloured thumbnail per chair;
# every PNG decodes and is not a single colour; the skipped shapes and the accuracy are on the page.
file(READ ${OUT}/report/index.html html)
string(REGEX MATCHALL "(src|href)=\"[^\"]+\"" refs "${html}")
list(LENGTH refs nrefs)
foreach(ref IN LISTS refs)
  string(REGEX REPLACE "^(src|href)=\"([^\"]+)\"$" "\\2" target "${ref}")
  if(target MATCHES "^(https?:|//)")
    message(FATAL_ERROR "the report refers to the network: ${target}")
  endif()
  if(NOT EXISTS ${OUT}/report/${target})
    message(FATAL_ERROR "the report refers to ${target}, which does not exist")
  endif()
endforeach()
file(GLOB shape_pngs ${OUT}/report/shapes/*.png)
file(GLOB part_pngs ${OUT}/report/parts/*.png)
list(LENGTH shape_pngs nshape)
list(LENGTH part_pngs npart)
if(NOT nshape EQUAL 12 OR NOT npart EQUAL 12)
  message(FATAL_ERROR "report: ${nshape} shape and ${npart} part thumbnails, expected 12 each")
endif()
if(NOT html MATCHES "nan" OR NOT html MATCHES "empty" OR NOT html MATCHES "accuracy against the ground truth")
  message(FATAL_ERROR "the report does not show the skipped shapes or the accuracy")
endif()
file(GLOB_RECURSE pngs ${OUT}/report/*.png)
execute_process(COMMAND ${PYTHON} ${PNG_CHECK} ${pngs} RESULT_VARIABLE code OUTPUT_VARIABLE pout ERROR_VARIABLE perr)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "PNG check failed:\n${pout}${perr}")
endif()
message(STATUS "report: ${nrefs} links, ${pout}")
# In Debian's chromium, headless, from file:// (when installed): the page's scripts ran (the stage times came from
# ../timings.js) and every image loaded (the page's own check, written into <body> after the load event).
if(CHROMIUM)
  execute_process(COMMAND ${CHROMIUM} --headless --no-sandbox --disable-gpu --virtual-time-budget=10000 --dump-dom
                          file://${OUT}/report/index.html
                  RESULT_VARIABLE code OUTPUT_VARIABLE dom ERROR_QUIET TIMEOUT 120)
  string(REGEX MATCH "data-images=\"([0-9]+)\"" m1 "${dom}")
  set(images ${CMAKE_MATCH_1})
  string(REGEX MATCH "data-broken-images=\"([0-9]+)\"" m2 "${dom}")
  set(broken ${CMAKE_MATCH_1})
  if(NOT code EQUAL 0 OR NOT images GREATER 0 OR NOT broken STREQUAL "0" OR NOT dom MATCHES "<td>templates</td>")
    message(FATAL_ERROR "chromium: exit ${code}, ${images} images, ${broken} not loaded, stage times filled in: "
                        "see the DOM:\n${dom}")
  endif()
  message(STATUS "chromium (headless, file://): ${images} images, all loaded; stage times shown")
else()
  message(STATUS "chromium not found: the page was not opened in a browser")
endif()

hash_tree(${OUT} before "^$")
hash_tree(${OUT} before_results "^fuzzy/pairs/")

# A second run: every stage is skipped, no file changes.
run_cli(0 second analyze ${IN} -o ${OUT} --threads 1)
string(REGEX MATCHALL "already done" skipped_stages "${second}")
list(LENGTH skipped_stages nskip)
if(NOT nskip EQUAL 5)
  message(FATAL_ERROR "a second run redid work (${nskip} of 5 stages skipped):\n${second}")
endif()
hash_tree(${OUT} again "^$")
if(NOT before STREQUAL again)
  message(FATAL_ERROR "a second run changed files")
endif()

# A rerun into the same OUT with other options or other shapes is refused before anything is written: finished
# stages would otherwise be skipped and their old results kept without a word.
run_cli(2 other_mode analyze ${IN} -o ${OUT} --mode intrinsic --quiet)
if(NOT other_mode MATCHES "--mode \"auto\"; this run asks for \"intrinsic\" \\(option --mode\\)" OR NOT other_mode MATCHES "delete fuzzy/, evaluate/, report/")
  message(FATAL_ERROR "a rerun with another --mode was not refused with the option and the stale folders named:\n${other_mode}")
endif()
run_cli(2 other_subset analyze ${IN} -o ${OUT} --learn-subset 5 --quiet)
if(NOT other_subset MATCHES "option --learn-subset" OR NOT other_subset MATCHES "delete templates/, evaluate/, report/")
  message(FATAL_ERROR "a rerun with another --learn-subset was not refused:\n${other_subset}")
endif()
run_cli(2 other_samples analyze ${IN} -o ${OUT} --samples 64 --quiet)
if(NOT other_samples MATCHES "option --samples" OR NOT other_samples MATCHES "delete fuzzy/, evaluate/, report/")
  message(FATAL_ERROR "a rerun with another --samples was not refused:\n${other_samples}")
endif()
run_cli(2 no_learn analyze ${IN} -o ${WORK}/never --no-learn)
if(NOT no_learn MATCHES "needs --template")
  message(FATAL_ERROR "analyze --no-learn without --template is not a usage error naming --template:\n${no_learn}")
endif()
file(WRITE ${IN}/extra.off "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
run_cli(2 other_shapes analyze ${IN} -o ${OUT} --quiet)
file(REMOVE ${IN}/extra.off)
if(NOT other_shapes MATCHES "extra.off is new in DIR")
  message(FATAL_ERROR "a rerun on other shapes was not refused, naming the new file:\n${other_shapes}")
endif()
hash_tree(${OUT} refused "^$")
if(NOT before STREQUAL refused)
  message(FATAL_ERROR "a refused rerun changed files in OUT")
endif()

# As an interruption leaves it: templates, evaluate, fuzzy and report unfinished, some of their files missing.
file(GLOB pairs_before RELATIVE ${OUT}/fuzzy/pairs ${OUT}/fuzzy/pairs/*.align)
file(REMOVE ${OUT}/templates/.done ${OUT}/templates/chair_000005.fit.json ${OUT}/templates/chair_000005.seg
     ${OUT}/templates/summary.json ${OUT}/evaluate/.done ${OUT}/evaluate/accuracy.json
     ${OUT}/fuzzy/.done ${OUT}/fuzzy/fuzzy.bin ${OUT}/fuzzy/collection.json ${OUT}/fuzzy/graph.txt
     ${OUT}/report/.done ${OUT}/report/index.html ${OUT}/report/parts/chair_000007.png ${OUT}/manifest.json)
list(GET pairs_before 0 one_pair)
file(REMOVE ${OUT}/fuzzy/pairs/${one_pair})
run_cli(0 third analyze ${IN} -o ${OUT} --threads 2 --quiet)
# The resume cache fuzzy/pairs/*.align records each alignment's wall time (the library's cache format), so a
# recomputed pair differs there; the same pairs must be there, and every other file must be identical.
file(GLOB pairs_after RELATIVE ${OUT}/fuzzy/pairs ${OUT}/fuzzy/pairs/*.align)
hash_tree(${OUT} resumed "^fuzzy/pairs/")
if(NOT before_results STREQUAL resumed OR NOT pairs_before STREQUAL pairs_after)
  message(FATAL_ERROR "a resumed run gave other files than the uninterrupted one:\n--- uninterrupted\n${before_results}\n--- resumed\n${resumed}")
endif()
message(STATUS "resumed run (files deleted): the same files, byte for byte")

# A real interruption: the templates' per-shape results and every later stage are deleted (the learned templates
# are kept, so the rerun goes straight to labeling), the run is killed after 4 s (the timeout kills the process:
# it falls in the labeling of the 12 shapes or just after), then run again to the end.
file(GLOB shape_results ${OUT}/templates/*.fit.json ${OUT}/templates/*.seg ${OUT}/templates/*.points.txt
     ${OUT}/templates/ply/*)
file(REMOVE ${shape_results} ${OUT}/templates/.done ${OUT}/templates/summary.json ${OUT}/manifest.json)
file(REMOVE_RECURSE ${OUT}/evaluate ${OUT}/fuzzy ${OUT}/report)
execute_process(COMMAND ${CLI} analyze ${IN} -o ${OUT} --threads 2 --quiet TIMEOUT 4 RESULT_VARIABLE killed
                OUTPUT_QUIET ERROR_QUIET)
file(GLOB fits_at_kill ${OUT}/templates/*.fit.json)
list(LENGTH fits_at_kill nfits)
message(STATUS "killed run: ${killed}; ${nfits} of 12 shapes were fitted when it was killed")
run_cli(0 fourth analyze ${IN} -o ${OUT} --threads 2 --quiet)
hash_tree(${OUT} after_kill "^fuzzy/pairs/")
if(NOT before_results STREQUAL after_kill)
  message(FATAL_ERROR "a run killed after 4 s and run again gave other files than the uninterrupted one:\n--- uninterrupted\n${before_results}\n--- after the kill\n${after_kill}")
endif()
message(STATUS "killed and resumed run: the same files, byte for byte")

# The stages' own options reach them: a run with other fuzzy samples and embedding dimensions (and the up axis,
# which both stages take) into another OUT, on the 12 chairs alone.
set(SMALL ${WORK}/small)
file(MAKE_DIRECTORY ${SMALL})
file(GLOB chairs ${IN}/chair_*)
file(COPY ${chairs} DESTINATION ${SMALL})
run_cli(0 passed analyze ${SMALL} -o ${WORK}/out_options --samples 32 --dimensions 8 --up 1 --quiet)
file(READ ${WORK}/out_options/fuzzy/collection.json options_collection)
string(JSON samples GET "${options_collection}" samples)
file(READ ${WORK}/out_options/fuzzy/.settings.json options_settings)
string(JSON dims GET "${options_settings}" dimensions)
if(NOT samples EQUAL 32 OR NOT dims EQUAL 8)
  message(FATAL_ERROR "analyze --samples 32 --dimensions 8 did not reach the fuzzy stage (samples ${samples}, dimensions ${dims})")
endif()
message(STATUS "analyze passes the stages' options on: fuzzy ran with 32 samples")

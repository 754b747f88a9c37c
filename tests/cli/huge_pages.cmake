# The tool starts itself once more with glibc.malloc.hugetlb=1 added to GLIBC_TUNABLES (huge_pages.hpp): `match -v`
# says which pages it runs on, the user's own GLIBC_TUNABLES setting of that tunable and SHAPESTRUCT_HUGE_PAGES=0
# are obeyed, the arguments reach the second start intact, and the map is the same byte for byte every way.
# Run by CTest as
#   cmake -DCLI=<path to shapestruct> -DWORK=<scratch folder> -P huge_pages.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

# A closed genus-0 mesh big enough for the matcher's samples: an octahedron refined four times onto the unit sphere.
set(v "1 0 0;-1 0 0;0 1 0;0 -1 0;0 0 1;0 0 -1")
set(f "0 2 4;2 1 4;1 3 4;3 0 4;2 0 5;1 2 5;3 1 5;0 3 5")
execute_process(COMMAND python3 -c "
import math, sys
V=[(1,0,0),(-1,0,0),(0,1,0),(0,-1,0),(0,0,1),(0,0,-1)]
F=[(0,2,4),(2,1,4),(1,3,4),(3,0,4),(2,0,5),(1,2,5),(3,1,5),(0,3,5)]
for _ in range(4):
    mid={}
    def m(a,b):
        k=(min(a,b),max(a,b))
        if k not in mid:
            p=[(V[a][i]+V[b][i])/2 for i in range(3)]; n=math.sqrt(sum(c*c for c in p))
            V.append(tuple(c/n for c in p)); mid[k]=len(V)-1
        return mid[k]
    G=[]
    for a,b,c in F:
        x,y,z=m(a,b),m(b,c),m(c,a); G+=[(a,x,z),(x,b,y),(z,y,c),(x,y,z)]
    F=G
for name, s in (('a', 1.0), ('b', 1.3)):
    with open(sys.argv[1]+'/'+name+'.off','w') as o:
        o.write('OFF\\n%d %d 0\\n' % (len(V), len(F)))
        for p in V: o.write('%.9g %.9g %.9g\\n' % (p[0]*s, p[1], p[2]))
        for t in F: o.write('3 %d %d %d\\n' % t)
" ${WORK} RESULT_VARIABLE code)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "could not write the test meshes (python3 exit code ${code})")
endif()

# run_match(NAME EXPECTED_MEMORY_LINE [ENV...]): `env ENV... shapestruct match a.off b.off -o NAME.map -v`.
function(run_match name expected)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env ${ARGN} ${CLI} match ${WORK}/a.off ${WORK}/b.off
                          -o ${WORK}/${name}.map -v --threads 1
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "${name}: shapestruct match exit code ${code}\n${out}\n${err}")
  endif()
  string(REGEX MATCH "memory: [^\n]*" said "${err}")
  if(NOT said MATCHES "${expected}")
    message(FATAL_ERROR "${name}: expected a line 'memory: ${expected}', got '${said}'\n${err}")
  endif()
endfunction()

# Where the kernel has transparent huge pages off, the tool does not restart and says so.
set(on "^memory: transparent huge pages")
set(thp "")
if(EXISTS /sys/kernel/mm/transparent_hugepage/enabled)
  file(READ /sys/kernel/mm/transparent_hugepage/enabled thp LIMIT 200)
endif()
if(thp STREQUAL "" OR thp MATCHES "\\[never\\]")
  set(on "^memory: ordinary pages \\(the kernel's transparent huge pages are off")
endif()
run_match(default "${on}" --unset=GLIBC_TUNABLES --unset=SHAPESTRUCT_HUGE_PAGES)
run_match(opted_out "^memory: ordinary pages \\(SHAPESTRUCT_HUGE_PAGES=0\\)"
          --unset=GLIBC_TUNABLES SHAPESTRUCT_HUGE_PAGES=0)
run_match(users_setting "^memory: as GLIBC_TUNABLES sets \\(glibc.malloc.hugetlb=0\\)"
          --unset=SHAPESTRUCT_HUGE_PAGES GLIBC_TUNABLES=glibc.malloc.hugetlb=0)
run_match(other_tunable "${on}" --unset=SHAPESTRUCT_HUGE_PAGES GLIBC_TUNABLES=glibc.malloc.perturb=0)
foreach(name opted_out users_setting other_tunable)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/default.map ${WORK}/${name}.map
                  RESULT_VARIABLE differ)
  if(differ)
    message(FATAL_ERROR "${name}.map differs from default.map: the pages must not change the map")
  endif()
endforeach()
message(STATUS "match ran on huge pages by default and as asked otherwise, the same map every way")

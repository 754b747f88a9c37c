# Consumer tests: prove that shapestruct works as an installed package (find_package) and as a subdirectory
# (add_subdirectory), and that the latter builds nothing but the library and leaks no global settings.
set(shapestruct_staging ${PROJECT_BINARY_DIR}/package-staging)

add_test(NAME package.install
         COMMAND ${CMAKE_COMMAND} --install ${PROJECT_BINARY_DIR} --prefix ${shapestruct_staging})
set_tests_properties(package.install PROPERTIES FIXTURES_SETUP shapestruct_installed LABELS unit)

add_test(NAME package.find_package_consumer
         COMMAND ${CMAKE_CTEST_COMMAND} --build-and-test
                 ${CMAKE_CURRENT_SOURCE_DIR}/package/find_package_consumer
                 ${PROJECT_BINARY_DIR}/package-consumers/find_package
                 --build-generator ${CMAKE_GENERATOR}
                 --build-options -DCMAKE_PREFIX_PATH=${shapestruct_staging} -DCMAKE_BUILD_TYPE=Release
                 --test-command consumer)
set_tests_properties(package.find_package_consumer PROPERTIES FIXTURES_REQUIRED shapestruct_installed LABELS unit)

add_test(NAME package.subdirectory_consumer
         COMMAND ${CMAKE_CTEST_COMMAND} --build-and-test
                 ${CMAKE_CURRENT_SOURCE_DIR}/package/subdirectory_consumer
                 ${PROJECT_BINARY_DIR}/package-consumers/subdirectory
                 --build-generator ${CMAKE_GENERATOR}
                 --build-options -DSHAPESTRUCT_SOURCE_DIR=${PROJECT_SOURCE_DIR} -DCMAKE_BUILD_TYPE=Release
                 --test-command consumer)
set_tests_properties(package.subdirectory_consumer PROPERTIES LABELS unit)

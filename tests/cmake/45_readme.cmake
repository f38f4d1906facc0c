# SPDX-License-Identifier: MIT
# The README's C example is extracted, compiled and run against the built library.
if(NOT CMAKE_C_FLAGS MATCHES "-fsanitize")
    add_test(NAME readme_c_example
        COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/readme/check_c_example.sh ${PROJECT_SOURCE_DIR}/README.md
                ${PROJECT_SOURCE_DIR}/include ${KAIROS_GENERATED_INCLUDE} $<TARGET_FILE:kairos> ${CMAKE_C_COMPILER})
    set_tests_properties(readme_c_example PROPERTIES LABELS readme)
endif()
# The README's Python example, run with the source tree's package.
if(NOT CMAKE_C_FLAGS MATCHES "-fsanitize" AND KAIROS_PYTHON3)
    add_test(NAME readme_python_example
        COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/readme/check_python_example.sh ${PROJECT_SOURCE_DIR}/README.md
                ${PROJECT_SOURCE_DIR}/python $<TARGET_FILE:kairos> ${KAIROS_PYTHON3})
    set_tests_properties(readme_python_example PROPERTIES LABELS readme SKIP_RETURN_CODE 77)
endif()

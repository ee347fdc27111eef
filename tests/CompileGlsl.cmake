# Compiles the shader that calls every GLSL decoder (shaders/check_compile.frag) with
# glslangValidator, from the Debian package glslang-tools. Looked up when the test runs, so
# installing the package needs no reconfigure. -G (SPIR-V for OpenGL) is the mode in which
# glslangValidator resolves #include.
#   cmake -DSHADER=check_compile.frag -DOUTPUT=check_compile.spv -P CompileGlsl.cmake
find_program(GLSLANG_VALIDATOR glslangValidator)
if(NOT GLSLANG_VALIDATOR)
  message(FATAL_ERROR "glslangValidator not found: install glslang-tools (scripts/install-deps.sh does)")
endif()
execute_process(COMMAND "${GLSLANG_VALIDATOR}" -G -o "${OUTPUT}" "${SHADER}" RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${SHADER} does not compile (glslangValidator exit code ${result})")
endif()

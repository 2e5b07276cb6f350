# lightsolver_embed_shaders(<target> <shader.comp>...): compiles each compute shader with glslc
# (found by find_package(Vulkan COMPONENTS glslc); its cache path works in every directory)
# (Vulkan 1.2 SPIR-V, -O, includes from this folder) into <name>.spv.inc, a comma-separated list
# of uint32 words that C++ includes inside an array initialiser. The folder with the .inc files is
# added to <target>'s include path. Dependencies on #included .glsl files come from glslc's
# depfile, so editing any shader rebuilds exactly what uses it.
set(LIGHTSOLVER_SHADER_DIR ${CMAKE_CURRENT_LIST_DIR})

function(lightsolver_embed_shaders target)
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/spirv)
  file(MAKE_DIRECTORY ${out_dir})
  set(outputs)
  foreach(source ${ARGN})
    get_filename_component(name ${source} NAME_WE)
    set(out ${out_dir}/${name}.spv.inc)
    add_custom_command(
      OUTPUT ${out}
      COMMAND ${Vulkan_GLSLC_EXECUTABLE} --target-env=vulkan1.2 -O -I ${LIGHTSOLVER_SHADER_DIR} -mfmt=num
              -MD -MF ${out}.d -o ${out} ${source}
      DEPENDS ${source}
      DEPFILE ${out}.d
      COMMENT "glslc ${name}.comp"
      VERBATIM)
    list(APPEND outputs ${out})
  endforeach()
  add_custom_target(${target}_spirv DEPENDS ${outputs})
  add_dependencies(${target} ${target}_spirv)
  target_include_directories(${target} PRIVATE ${out_dir})
endfunction()

# Included by the top-level CMakeLists.txt (in its directory, where dpscope_decoder is made:
# a generated source must be made in the directory of the target that compiles it).
# The shipped parameter databases (drives/databases/<family>.params), compiled into the decoder
# library: a generated source holds their texts (embed_databases.cmake), remade when a database
# changes; a database added or removed is seen at the next build (CONFIGURE_DEPENDS).
file(GLOB dpscope_parameter_databases CONFIGURE_DEPENDS
     ${CMAKE_CURRENT_LIST_DIR}/databases/*.params)
list(SORT dpscope_parameter_databases)
set(dpscope_shipped_databases_cpp ${PROJECT_BINARY_DIR}/generated/drives/shipped_databases.cpp)
add_custom_command(
    OUTPUT ${dpscope_shipped_databases_cpp}
    COMMAND ${CMAKE_COMMAND} -D OUTPUT=${dpscope_shipped_databases_cpp}
            -D SOURCE_DIR=${PROJECT_SOURCE_DIR} "-D FILES=${dpscope_parameter_databases}"
            -P ${CMAKE_CURRENT_LIST_DIR}/embed_databases.cmake
    DEPENDS ${dpscope_parameter_databases} ${CMAKE_CURRENT_LIST_DIR}/embed_databases.cmake
    COMMENT "Embedding the shipped parameter databases"
    VERBATIM)
target_sources(dpscope_decoder PRIVATE ${dpscope_shipped_databases_cpp})

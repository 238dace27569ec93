# Writes OUTPUT from INPUT with MOORSIM_VERSION_STRING = PROJECT_VERSION + "git describe" of
# SOURCE_DIR. Run at every build (core/CMakeLists.txt, target moorsim_version), not only at
# configure time, so the version every output records names the commit that was built;
# configure_file rewrites OUTPUT only when the text changes, so an unchanged version
# recompiles nothing.
execute_process(COMMAND git describe --always --dirty --tags
                WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE MOORSIM_GIT_DESCRIBE OUTPUT_STRIP_TRAILING_WHITESPACE
                ERROR_QUIET)
if(NOT MOORSIM_GIT_DESCRIBE)
  set(MOORSIM_GIT_DESCRIBE "unknown")
endif()
set(MOORSIM_VERSION_STRING "${PROJECT_VERSION}+${MOORSIM_GIT_DESCRIBE}")
configure_file(${INPUT} ${OUTPUT} @ONLY)

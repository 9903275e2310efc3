# Writes the current git SHA (with "-dirty" when the tree has uncommitted changes) into a header,
# at build time, so provenance lines name the commit that was actually built.
# Usage: cmake -DSOURCE_DIR=... -DOUTPUT=... -P GitSha.cmake
execute_process(COMMAND git rev-parse --short=12 HEAD WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE sha OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT sha)
  set(sha "unknown")
else()
  execute_process(COMMAND git status --porcelain --untracked-files=no WORKING_DIRECTORY ${SOURCE_DIR}
                  OUTPUT_VARIABLE dirty OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(dirty)
    string(APPEND sha "-dirty")
  endif()
endif()
file(WRITE "${OUTPUT}.tmp" "#pragma once\n// Generated at build time by cmake/GitSha.cmake.\n#define ALLANLAB_GIT_SHA \"${sha}\"\n")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")

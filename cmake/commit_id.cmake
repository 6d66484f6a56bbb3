# Run at every build (src/run/CMakeLists.txt): writes OUT with the commit of the code the
# build is made of, that is the last commit that changed `paths` below (the sources and CMake
# files under SRC, not the docs, cases or tests), and "-dirty" when they differ from it. So a
# run's summary.json and checkpoints name the code they came from, not the commit CMake was
# configured at, and a commit of docs or results neither rebuilds nor changes the identity
# that `report --resume` and `run --restart` check. The file is only rewritten when its text
# changes: an unchanged id recompiles nothing.
set(paths CMakeLists.txt cmake src meshing render ":(exclude)*.md")  # src holds the scenes' REFERENCE.md
set(commit "no-git")
if(GIT)
  execute_process(COMMAND ${GIT} log -1 --format=%h --abbrev=12 -- ${paths} WORKING_DIRECTORY ${SRC}
    OUTPUT_VARIABLE last OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
  if(rc EQUAL 0 AND NOT last STREQUAL "")
    set(commit "${last}")
    # 1: they differ; another code is git's own error, which says nothing about them.
    execute_process(COMMAND ${GIT} diff --quiet HEAD -- ${paths} WORKING_DIRECTORY ${SRC}
      RESULT_VARIABLE dirty ERROR_QUIET)
    if(dirty EQUAL 1)
      string(APPEND commit "-dirty")
    endif()
  endif()
endif()
file(WRITE "${OUT}.tmp" "#define DSPDEM_COMMIT \"${commit}\"\n")
configure_file("${OUT}.tmp" "${OUT}" COPYONLY)  # rewrites OUT only when the text differs
file(REMOVE "${OUT}.tmp")

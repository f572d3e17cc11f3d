# Included by the check_*.cmake scripts.

# Fails unless `path` exists and is not empty; `writer` names what should have written it.
function(expect_nonempty_file path writer)
  if(NOT EXISTS "${path}")
    message(FATAL_ERROR "${writer} did not write ${path}")
  endif()
  file(SIZE "${path}" size)
  if(size EQUAL 0)
    message(FATAL_ERROR "${writer} wrote an empty ${path}")
  endif()
endfunction()

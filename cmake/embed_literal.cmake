# The C++ string literal of a file's content, for the build-time embedding scripts
# (embed_data.cmake: data/; embed_web.cmake: skylight view's page): raw literals delimited by
# DELIM, split into pieces the compiler concatenates (compilers limit a single literal token).
# Appends to the variable named OUT; a content holding ")DELIM\"" is a fatal error naming WHAT.
function(skylight_append_literal OUT content DELIM WHAT INDENT)
  string(FIND "${content}" ")${DELIM}\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${WHAT} contains the raw-string delimiter")
  endif()
  set(text "${${OUT}}")
  string(LENGTH "${content}" len)
  set(pos 0)
  while(pos LESS len)
    string(SUBSTRING "${content}" ${pos} 60000 chunk)
    string(APPEND text "${INDENT}R\"${DELIM}(${chunk})${DELIM}\"\n")
    math(EXPR pos "${pos} + 60000")
  endwhile()
  if(len EQUAL 0)
    string(APPEND text "${INDENT}\"\"\n")
  endif()
  set(${OUT} "${text}" PARENT_SCOPE)
endfunction()

# Writes OUT: the device engine's sources (and the Arduino glue) as C++ raw string literals, so
# avar export writes the very sources this avar was built and tested with. Run by
# device/CMakeLists.txt with -DOUT=... -DENTRIES="destination=source|..." (sources absolute).
set(text "// Generated from the sources at build time (device/export/embed_sources.cmake): do not edit.\n")
string(APPEND text "const EmbeddedSource kEmbeddedSources[] = {\n")
string(REPLACE "|" ";" ENTRIES "${ENTRIES}")
foreach(entry IN LISTS ENTRIES)
  string(REGEX MATCH "^([^=]+)=(.+)$" _ "${entry}")
  set(destination "${CMAKE_MATCH_1}")
  file(READ "${CMAKE_MATCH_2}" content)
  string(APPEND text "    {\"${destination}\", R\"avar_embed(${content})avar_embed\"},\n")
endforeach()
string(APPEND text "};\n")
file(WRITE "${OUT}.tmp" "${text}")
file(COPY_FILE "${OUT}.tmp" "${OUT}" ONLY_IF_DIFFERENT)

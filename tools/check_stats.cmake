# Parses a --stats JSON file with CMake's JSON reader (no python on a fresh
# Debian) and checks the fields a user relies on.
file(READ ${JSON} j)
string(JSON w GET "${j}" terrain width)
string(JSON voids GET "${j}" terrain voids_filled)
string(JSON tris GET "${j}" frame triangles)
string(JSON npools LENGTH "${j}" pools)
string(JSON pool0 GET "${j}" pools 0 pool)
string(JSON method GET "${j}" method)
if(NOT w EQUAL 1201 OR NOT voids EQUAL 7652 OR tris LESS 1000 OR NOT npools EQUAL 10
   OR NOT pool0 STREQUAL "heights_bytes" OR NOT method STREQUAL "brute")
  message(FATAL_ERROR "unexpected stats: width ${w} voids ${voids} triangles ${tris} pools ${npools}")
endif()
message(STATUS "stats JSON ok: ${w} wide, ${voids} voids, ${tris} triangles")

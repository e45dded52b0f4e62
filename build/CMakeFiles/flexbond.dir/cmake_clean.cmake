file(REMOVE_RECURSE
  "CMakeFiles/flexbond.dir/src/core/error.c.o"
  "CMakeFiles/flexbond.dir/src/core/error.c.o.d"
  "libflexbond.a"
  "libflexbond.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang C)
  include(CMakeFiles/flexbond.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()

file(REMOVE_RECURSE
  "libflexbond.a"
)

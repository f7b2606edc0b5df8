# Sanitizers for every GASP target (GASP_SANITIZE, a cache string defined in the top-level
# CMakeLists.txt; scripts/sanitize.sh builds and runs the tests with address,undefined).
#
# gasp_set_sanitizers(<target>): when GASP_SANITIZE is not empty, compiles the target with
# -fsanitize=<GASP_SANITIZE> -fno-omit-frame-pointer (and -fno-sanitize-recover=undefined when
# undefined is in the list, so a UBSan finding ends the process and fails its test) and links it
# with -fsanitize=<GASP_SANITIZE>. The link option is PUBLIC on libraries: whatever links a
# sanitized GASP library (a program, a test, a consumer of the installed package) links the
# sanitizer runtimes too, which ASan needs to come first. Empty GASP_SANITIZE: nothing changes.
function(gasp_set_sanitizers target)
  if("${GASP_SANITIZE}" STREQUAL "")
    return()
  endif()
  set(compile -fsanitize=${GASP_SANITIZE} -fno-omit-frame-pointer)
  string(REPLACE "," ";" sanitizers "${GASP_SANITIZE}")
  if("undefined" IN_LIST sanitizers)
    list(APPEND compile -fno-sanitize-recover=undefined)
  endif()
  target_compile_options(${target} PRIVATE ${compile})
  if("address" IN_LIST sanitizers)
    # Eigen 3.4 stops trusting malloc's 16-byte alignment when __SANITIZE_ADDRESS__ is defined and
    # switches to its own over-allocating aligned_malloc / aligned_free. PCL, MRPT, Ceres and OpenCV
    # are not rebuilt with ASan: Eigen storage they allocate (a PCL feature estimator's matrices,
    # a point cloud's points) and GASP's inlined destructors free would be freed the other way
    # (ASan: heap-buffer-overflow in Eigen::internal::handmade_aligned_free). Keeping malloc's
    # alignment (glibc and ASan both give 16 bytes on x86-64) keeps GASP's Eigen ABI that of the
    # libraries it links.
    target_compile_definitions(${target} PRIVATE EIGEN_MALLOC_ALREADY_ALIGNED=1)
  endif()
  get_target_property(type ${target} TYPE)
  if(type MATCHES "LIBRARY$")
    target_link_options(${target} PUBLIC -fsanitize=${GASP_SANITIZE})
  else()
    target_link_options(${target} PRIVATE -fsanitize=${GASP_SANITIZE})
  endif()
endfunction()

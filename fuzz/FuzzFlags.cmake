# GASP_FUZZ=ON (top-level CMakeLists.txt includes this before any target is defined): every GASP
# library of this build is compiled for libFuzzer's coverage and with ASan + UBSan, so that the
# fuzz targets of fuzz/ see the readers' branches and any memory error or undefined behaviour in
# them is a crash. A build folder of its own (build/fuzz, scripts/fuzz.sh); the normal build is
# not touched: nothing here runs when GASP_FUZZ is OFF.
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR
    "GASP_FUZZ=ON needs clang (libFuzzer ships with it), but the C++ compiler is "
    "${CMAKE_CXX_COMPILER_ID} (${CMAKE_CXX_COMPILER}). Configure a separate build folder with clang, e.g.\n"
    "  cmake -S . -B build/fuzz -DCMAKE_CXX_COMPILER=clang++ -DGASP_FUZZ=ON -DGASP_BUILD_TESTS=OFF "
    "-DGASP_BUILD_BENCHMARKS=OFF -DGASP_BUILD_BASELINES=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo\n"
    "or run scripts/fuzz.sh.")
endif()
# Coverage instrumentation without libFuzzer's main (only the fuzz targets link that), ASan and
# UBSan; a UBSan report aborts (-fno-sanitize-recover) so that libFuzzer keeps it as a crash.
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
                    -fno-omit-frame-pointer)
add_link_options(-fsanitize=address,undefined)

# cmake_version.cmake - writes celscanConfigVersion.cmake with CMake's own helper
# (cmake -DOUT=FILE -DVERSION=X.Y.Z -P tools/cmake_version.cmake, from install_meta.sh).
# ARCH_INDEPENDENT: the package holds libraries for several targets, so a
# 32-bit microcontroller build must accept it as well as the 64-bit host.
include(CMakePackageConfigHelpers)
write_basic_package_version_file("${OUT}" VERSION "${VERSION}" COMPATIBILITY SameMinorVersion
                                 ARCH_INDEPENDENT)

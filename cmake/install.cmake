# What `cmake --install` puts where, the CMake package and pkg-config file for programs that
# link the library, the man page, bash completion and the .deb (cpack). docs/install.md.
include(CMakePackageConfigHelpers)

# The program, the library (static) and its public headers.
set(RGBDVO_INSTALL_TARGETS rgbdvo_lib)
if(RGBDVO_WITH_KINECT)
  list(APPEND RGBDVO_INSTALL_TARGETS rgbdvo_kinect)
endif()
install(TARGETS rgbdvo RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS ${RGBDVO_INSTALL_TARGETS} EXPORT rgbdvoTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# Public: the folders a program using the library includes, and the headers they include in
# turn. Private (not installed): SIFT's and Lucas-Kanade's internals, the SIMD kernels, the PNG
# decoder and the MCAP reader, util/ (but the queue a KinectSource holds), calibration, synthetic
# scenes, and the ROS bag source, whose library is not installed. tests/install/install_test.sh compiles every
# installed header against the installed tree alone.
set(RGBDVO_PUBLIC_HEADER_DIRS odometry sources sensor io evaluation pipeline)
set(RGBDVO_PUBLIC_HEADERS
    estimation/depth_term.hpp estimation/motion_check.hpp estimation/motion_estimate.hpp
    estimation/point_pair.hpp estimation/ransac.hpp estimation/refine.hpp
    features/features.hpp features/matching.hpp features/track_options.hpp
    geometry/geometry.hpp geometry/motion_prior.hpp)
if(RGBDVO_WITH_KINECT)
  list(APPEND RGBDVO_PUBLIC_HEADER_DIRS capture)
  list(APPEND RGBDVO_PUBLIC_HEADERS util/bounded_queue.hpp)
endif()
foreach(dir ${RGBDVO_PUBLIC_HEADER_DIRS})
  install(DIRECTORY include/rgbdvo/${dir} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rgbdvo
          PATTERN "png_decoder.hpp" EXCLUDE
          PATTERN "mcap_reader.hpp" EXCLUDE
          PATTERN "rosbag_source.hpp" EXCLUDE)
endforeach()
foreach(header ${RGBDVO_PUBLIC_HEADERS})
  get_filename_component(dir ${header} DIRECTORY)
  install(FILES include/rgbdvo/${header} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rgbdvo/${dir})
endforeach()

# find_package(rgbdvo): rgbdvo::rgbdvo (and rgbdvo::kinect).
set(RGBDVO_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/rgbdvo)
install(EXPORT rgbdvoTargets NAMESPACE rgbdvo:: DESTINATION ${RGBDVO_CMAKE_DIR})
configure_package_config_file(cmake/rgbdvoConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/rgbdvoConfig.cmake
                              INSTALL_DESTINATION ${RGBDVO_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/rgbdvoConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/rgbdvoConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/rgbdvoConfigVersion.cmake
        DESTINATION ${RGBDVO_CMAKE_DIR})

# rgbdvo.pc, relocatable: the prefix is found from the file's own place.
file(RELATIVE_PATH RGBDVO_PC_TO_PREFIX /${CMAKE_INSTALL_LIBDIR}/pkgconfig /)
configure_file(cmake/rgbdvo.pc.in ${CMAKE_CURRENT_BINARY_DIR}/rgbdvo.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/rgbdvo.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# Calibrations (found by name: --calib tum_fr1), the documentation and the licence.
install(DIRECTORY calib/ DESTINATION ${CMAKE_INSTALL_DATADIR}/rgbdvo/calib FILES_MATCHING PATTERN "*.yaml")
install(FILES README.md LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs)

# Bash completion: subcommands, and each subcommand's flags as its --help lists them.
install(FILES scripts/rgbdvo-completion.bash DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions
        RENAME rgbdvo)

# The man page, from the program's own --help (Debian's help2man; skipped without it).
find_program(HELP2MAN help2man)
if(HELP2MAN)
  add_custom_command(OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/rgbdvo.1
                     COMMAND bash ${PROJECT_SOURCE_DIR}/scripts/make_manpage.sh $<TARGET_FILE:rgbdvo>
                             ${CMAKE_CURRENT_BINARY_DIR}/rgbdvo.1
                     DEPENDS rgbdvo ${PROJECT_SOURCE_DIR}/scripts/make_manpage.sh
                     COMMENT "Man page rgbdvo.1 from --help")
  add_custom_target(rgbdvo_manpage ALL DEPENDS ${CMAKE_CURRENT_BINARY_DIR}/rgbdvo.1)
  install(FILES ${CMAKE_CURRENT_BINARY_DIR}/rgbdvo.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
else()
  message(STATUS "help2man not found: no man page (scripts/setup.sh installs it)")
endif()

# cpack: a .deb for /usr whose Depends come from the libraries the program links (dpkg-shlibdeps).
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME rgbdvo)
set(CPACK_PACKAGE_VENDOR rgbdvo)
set(CPACK_PACKAGE_CONTACT "rgbdvo maintainers <rgbdvo@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "visual odometry for Kinect-style RGB-D cameras")
set(CPACK_PACKAGE_DESCRIPTION "SIFT features matched between frames, lifted to 3D with the depth \
image, RANSAC over 4-match hypotheses and a robust refinement (Fiala & Ufkes 2011, and beyond). \
Runs on TUM RGB-D and fakenect recordings or live from a Kinect v1, and evaluates ATE and RPE. \
Also holds the static library, its headers and CMake package (building against them needs the \
-dev packages of OpenCV, Eigen, ISA-L and libfreenect).")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# OpenCV's image codecs and window library are loaded when first needed (src/io/opencv_codecs.cpp,
# apps/opencv_window.cpp), not linked, so dpkg-shlibdeps does not see them: their packages, named
# after the libraries' sonames.
set(RGBDVO_LOADED_PACKAGES "")
foreach(module imgcodecs highgui)
  get_target_property(soname opencv_${module} IMPORTED_SONAME_RELEASE)
  if(soname MATCHES "^libopencv_${module}\\.so\\.([0-9]+)$")
    list(APPEND RGBDVO_LOADED_PACKAGES "libopencv-${module}${CMAKE_MATCH_1}")
  endif()
endforeach()
list(JOIN RGBDVO_LOADED_PACKAGES ", " CPACK_DEBIAN_PACKAGE_DEPENDS)
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "gnuplot-nox")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "libfreenect-bin")
include(CPack)

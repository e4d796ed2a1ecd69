# The Debian packages, built with CPack from the install rules (`scripts/package`):
#   flat2d      the service, the tools, units, configuration, the API schema
#   flat2d-dev  the client library, its headers and CMake package configuration
# Runtime dependencies come from dpkg-shlibdeps on the installed binaries. Each description
# starts with its summary line (no CPACK_PACKAGE_DESCRIPTION_SUMMARY, which CPack would prepend).
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME flat2d)
set(CPACK_PACKAGE_VENDOR "flat2d")
set(CPACK_PACKAGE_CONTACT "flat2d maintainers <flat2d@localhost>")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)

set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL runtime dev)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)

set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME flat2d)
set(CPACK_DEBIAN_RUNTIME_DESCRIPTION
    "fixed-memory LiDAR localization daemon against 2D prior maps
flat2dd reads Velodyne LiDAR packets and CAN odometry, scan-matches each revolution's
structure grid against a compressed 2D prior map and serves the local-to-global transform
and poses over a Unix socket. With the flat2d client and the offline map tools.")
set(CPACK_DEBIAN_RUNTIME_PACKAGE_DEPENDS procps)  # /bin/kill, the unit's ExecReload
set(CPACK_DEBIAN_RUNTIME_PACKAGE_RECOMMENDS systemd)
set(debian_dir ${PROJECT_SOURCE_DIR}/packaging/debian)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_CONTROL_EXTRA
    ${debian_dir}/conffiles ${debian_dir}/postinst ${debian_dir}/prerm ${debian_dir}/postrm)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_CONTROL_STRICT_PERMISSION ON)

set(CPACK_DEBIAN_DEV_PACKAGE_NAME flat2d-dev)
set(CPACK_DEBIAN_DEV_DESCRIPTION
    "client library for the flat2d localization daemon
A C++ client of flat2dd's socket API (find_package(flat2d), flat2d::client).")
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS "flat2d (= ${PROJECT_VERSION}), libprotobuf-dev")
set(CPACK_DEBIAN_DEV_PACKAGE_SHLIBDEPS OFF)

include(CPack)

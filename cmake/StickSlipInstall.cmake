# `cmake --install build --prefix P`: the two programs, the desktop entry, the icon theme files,
# man pages and the documentation, laid out as the freedesktop and FHS conventions expect, so the
# installed app runs from P (the programs link the project's libraries statically).
set(CMAKE_INSTALL_DOCDIR "share/doc/stickslip" CACHE PATH "Documentation (share/doc/stickslip)")
include(GNUInstallDirs)

install(TARGETS stickslip-cli RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
if(TARGET stickslip)
  install(TARGETS stickslip RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
  install(FILES "${PROJECT_SOURCE_DIR}/resources/stickslip.desktop"
          DESTINATION "${CMAKE_INSTALL_DATADIR}/applications")
  install(FILES "${PROJECT_SOURCE_DIR}/resources/icons/stickslip.svg"
          DESTINATION "${CMAKE_INSTALL_DATADIR}/icons/hicolor/scalable/apps")
  foreach(px 16 32 48 64 128 256)
    install(FILES "${PROJECT_SOURCE_DIR}/resources/icons/stickslip-${px}.png"
            DESTINATION "${CMAKE_INSTALL_DATADIR}/icons/hicolor/${px}x${px}/apps" RENAME stickslip.png)
  endforeach()
  install(FILES "${PROJECT_SOURCE_DIR}/resources/stickslip.1" DESTINATION "${CMAKE_INSTALL_MANDIR}/man1")
endif()
# Generated after every CLI build (app/cli/CMakeLists.txt).
install(FILES "${PROJECT_BINARY_DIR}/man/stickslip-cli.1" DESTINATION "${CMAKE_INSTALL_MANDIR}/man1")

# The Python module, where Debian's python3 looks for packages under a prefix
# (P/lib/python3/dist-packages; for another prefix add that folder to PYTHONPATH).
if(TARGET stickslip_python)
  install(TARGETS stickslip_python LIBRARY DESTINATION "lib/python3/dist-packages")
endif()

install(FILES "${PROJECT_SOURCE_DIR}/README.md" "${PROJECT_SOURCE_DIR}/LICENSE"
        DESTINATION "${CMAKE_INSTALL_DOCDIR}")
install(DIRECTORY "${PROJECT_SOURCE_DIR}/docs/" DESTINATION "${CMAKE_INSTALL_DOCDIR}")

# All third-party dependencies, found once, with the Debian 12 quirks handled here and nowhere else.
# Every package comes from Debian's archive; cmake/packages.txt lists them and cmake/setup.sh installs them.

find_package(Threads REQUIRED)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(TBB REQUIRED)
find_package(nlohmann_json 3.11 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(spdlog REQUIRED)
find_package(PNG REQUIRED)
find_package(nanoflann REQUIRED)
find_package(embree 3 REQUIRED)
# CGAL (header-only here): hole filling of scanned meshes (core/sim/MeshRepair.cpp).
find_package(CGAL 5.5 REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(BULLET REQUIRED IMPORTED_TARGET bullet)

# Trap 3: VTK (pulled in by PCL's config) leaves VTK::mpi pointing at MPI::MPI_C.
find_package(MPI REQUIRED COMPONENTS C)

# Trap 2: PCL wires a component's internal dependencies only if those were processed first,
# so the components are listed in dependency order.
set(SCANPICK_PCL_COMPONENTS common kdtree octree search sample_consensus filters io features
                            registration segmentation)
# Its find_package(VTK) also finds Qt5 through VTK's GUISupportQt; keep Qt5 from claiming the
# versionless Qt:: target names, which belong to Qt6 below.
set(QT_NO_CREATE_VERSIONLESS_TARGETS ON)
find_package(PCL 1.13 REQUIRED COMPONENTS ${SCANPICK_PCL_COMPONENTS})
unset(QT_NO_CREATE_VERSIONLESS_TARGETS)

# Trap 1: Debian's PCLConfig.cmake adds VTK::GUISupportQt (a Qt5 module) to the interface of
# several PCL targets. No PCL shared library links Qt, so it is dropped before Qt6 is found.
# pcl_2d and pcl_surface come in as dependencies of pcl_features without being listed.
foreach(component IN LISTS SCANPICK_PCL_COMPONENTS ITEMS 2d surface)
  if(TARGET pcl_${component})
    get_target_property(_libs pcl_${component} INTERFACE_LINK_LIBRARIES)
    if(_libs)
      list(REMOVE_ITEM _libs VTK::GUISupportQt)
      set_target_properties(pcl_${component} PROPERTIES INTERFACE_LINK_LIBRARIES "${_libs}")
    endif()
  endif()
endforeach()

# One interface target for the PCL pieces the core uses (never ${PCL_LIBRARIES}).
add_library(scanpick_pcl INTERFACE)
foreach(component IN LISTS SCANPICK_PCL_COMPONENTS)
  target_link_libraries(scanpick_pcl INTERFACE pcl_${component})
endforeach()
target_include_directories(scanpick_pcl SYSTEM INTERFACE ${PCL_INCLUDE_DIRS})
target_compile_definitions(scanpick_pcl INTERFACE ${PCL_DEFINITIONS})

if(SCANPICK_BUILD_DEVICES)
  pkg_check_modules(ARAVIS REQUIRED IMPORTED_TARGET aravis-0.8)
  pkg_check_modules(FREENECT REQUIRED IMPORTED_TARGET libfreenect)
  pkg_check_modules(LIBUSB REQUIRED IMPORTED_TARGET libusb-1.0)
  pkg_check_modules(OPENNI2 REQUIRED IMPORTED_TARGET libopenni2)
  pkg_check_modules(OPENNI1 IMPORTED_TARGET libopenni)
  if(SCANPICK_WITH_PHOXI_API)
    find_package(PhoXi CONFIG REQUIRED PATHS $ENV{PHOXI_CONTROL_PATH})
  endif()
endif()

if(SCANPICK_BUILD_GUI)
  find_package(Qt6 6.4 REQUIRED COMPONENTS Core Gui Widgets OpenGL OpenGLWidgets Concurrent Test LinguistTools)
  # Trap 3 again for the viewport's VTK modules; never request VTK's Qt5-only GUISupportQt.
  find_package(VTK 9.1 REQUIRED COMPONENTS CommonCore CommonDataModel CommonColor CommonTransforms
               FiltersSources FiltersGeneral InteractionStyle InteractionWidgets RenderingCore
               RenderingOpenGL2 RenderingAnnotation RenderingFreeType RenderingContextOpenGL2)
endif()

if(SCANPICK_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(SCANPICK_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()

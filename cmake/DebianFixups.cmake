# Debian 12's OpenImageIO target lists /usr/include/opencv4, which the
# package does not depend on; drop it so configuring does not fail.
if(TARGET OpenImageIO::OpenImageIO)
  get_target_property(_oiio_inc OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
  if(_oiio_inc)
    list(FILTER _oiio_inc EXCLUDE REGEX "opencv")
    set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_oiio_inc}")
  endif()
endif()

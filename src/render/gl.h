// The one place that includes the OpenGL headers: OSMesa's GL with every entry point of GL 2+
// declared (GL_GLEXT_PROTOTYPES), which -lOSMesa exports directly, so no loader is needed.
// Only render/*.cpp include this; the public headers stay free of GL types.
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

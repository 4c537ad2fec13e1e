#pragma once
// Which OpenGL the raster uses: auto (a GPU through EGL when there is one, else OSMesa, else
// EGL's surfaceless platform), egl (a device, or Mesa's surfaceless platform) or osmesa.
namespace irad {

enum class GlBackend { Auto, Egl, OsMesa };

} // namespace irad

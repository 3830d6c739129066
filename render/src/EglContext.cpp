// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/EglContext.h>

#include <strata/Error.h>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <dlfcn.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace strata::render {

namespace {

const char* const INSTALL_HINT = "install libegl-mesa0 and libgl1-mesa-dri, or use a machine with a GPU";

std::string eglErrorName(EGLint code)
{
    switch (code) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    default: return "EGL error 0x" + [code] {
        char buffer[16];
        std::snprintf(buffer, sizeof(buffer), "%x", unsigned(code));
        return std::string(buffer);
    }();
    }
}

std::string lastEglError() { return eglErrorName(eglGetError()); }

/// True when the space-separated extension list `extensions` (may be null)
/// holds `name`.
bool hasExtension(const char* extensions, const char* name)
{
    if (!extensions) {
        return false;
    }
    const std::size_t length = std::strlen(name);
    for (const char* p = extensions; (p = std::strstr(p, name)) != nullptr; p += length) {
        const bool startOk = p == extensions || p[-1] == ' ';
        const bool endOk = p[length] == ' ' || p[length] == '\0';
        if (startOk && endOk) {
            return true;
        }
    }
    return false;
}

/// libepoxy aborts the process when it cannot load libEGL or libGL: check
/// first, so a machine without them gets a strata::Error instead.
void checkLibrariesLoadable()
{
    auto loadable = [](const char* name) {
        void* handle = ::dlopen(name, RTLD_LAZY | RTLD_LOCAL);
        if (handle) {
            ::dlclose(handle);
        }
        return handle != nullptr;
    };
    if (!loadable("libEGL.so.1")) {
        const char* reason = ::dlerror();
        throw Error(ErrorKind::Gl, std::string("no EGL: cannot load libEGL.so.1 (") + (reason ? reason : "not found") +
                    "); install libegl1 and libegl-mesa0, or a GPU driver with EGL");
    }
    if (!loadable("libOpenGL.so.0") && !loadable("libGL.so.1")) {
        throw Error(ErrorKind::Gl, "no OpenGL: cannot load libOpenGL.so.0 or libGL.so.1; install libopengl0 and libgl1-mesa-dri, "
                    "or a GPU driver");
    }
}

/// What a context holds, released in reverse order on destruction.
struct EglResources
{
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    EGLSurface surface = EGL_NO_SURFACE; ///< 1×1 pbuffer, only without EGL_KHR_surfaceless_context

    EglResources() = default;
    EglResources(const EglResources&) = delete;
    EglResources& operator=(const EglResources&) = delete;

    ~EglResources()
    {
        if (display == EGL_NO_DISPLAY) {
            return;
        }
        if (context != EGL_NO_CONTEXT && eglGetCurrentContext() == context) {
            eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        }
        if (surface != EGL_NO_SURFACE) {
            eglDestroySurface(display, surface);
        }
        if (context != EGL_NO_CONTEXT) {
            eglDestroyContext(display, context);
        }
        // The display is not terminated: eglGetPlatformDisplayEXT hands the
        // same EGLDisplay to everyone in the process (the embedding
        // application, another EglContext), and eglTerminate would pull it
        // from under them. Initialising it again is a no-op.
        if (eglGetCurrentContext() == EGL_NO_CONTEXT) {
            eglReleaseThread();
        }
    }
};

/// Tries to get a current OpenGL 4.5 core context on `display`, filling
/// the empty `handles`. On failure returns false and sets `reason`; the
/// caller destroys `handles`, which releases what was acquired.
bool tryDisplay(EGLDisplay display, EglResources& handles, std::string& reason)
{
    if (display == EGL_NO_DISPLAY) {
        reason = "eglGetPlatformDisplayEXT failed: " + lastEglError();
        return false;
    }
    EGLint major = 0;
    EGLint minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
        reason = "eglInitialize failed: " + lastEglError();
        return false;
    }
    handles.display = display;

    if (!eglBindAPI(EGL_OPENGL_API)) {
        reason = "no desktop OpenGL (eglBindAPI failed: " + lastEglError() + ")";
        return false;
    }

    const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
    const bool surfaceless = hasExtension(extensions, "EGL_KHR_surfaceless_context");

    // A config: with pbuffer support if we can get one (needed without
    // surfaceless contexts), else any OpenGL config, else none at all.
    EGLConfig config = nullptr;
    EGLint count = 0;
    const EGLint pbufferAttributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                        EGL_NONE};
    const EGLint anyAttributes[] = {EGL_SURFACE_TYPE, 0, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    bool haveConfig = eglChooseConfig(display, pbufferAttributes, &config, 1, &count) && count > 0;
    if (!haveConfig && surfaceless) {
        haveConfig = eglChooseConfig(display, anyAttributes, &config, 1, &count) && count > 0;
        if (!haveConfig && hasExtension(extensions, "EGL_KHR_no_config_context")) {
            config = EGL_NO_CONFIG_KHR;
            haveConfig = true;
        }
    }
    if (!haveConfig) {
        reason = "no OpenGL EGL config (eglChooseConfig: " + lastEglError() + ")";
        return false;
    }

    const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                        4,
                                        EGL_CONTEXT_MINOR_VERSION,
                                        5,
                                        EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                        EGL_NONE};
    handles.context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
    if (handles.context == EGL_NO_CONTEXT) {
        reason = "no OpenGL 4.5 core context (eglCreateContext failed: " + lastEglError() + ")";
        return false;
    }

    if (!surfaceless) {
        const EGLint surfaceAttributes[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
        handles.surface = eglCreatePbufferSurface(display, config, surfaceAttributes);
        if (handles.surface == EGL_NO_SURFACE) {
            reason = "no surfaceless contexts and no pbuffer (eglCreatePbufferSurface failed: " + lastEglError() + ")";
            return false;
        }
    }
    if (!eglMakeCurrent(display, handles.surface, handles.surface, handles.context)) {
        reason = "eglMakeCurrent failed: " + lastEglError();
        return false;
    }
    if (!epoxy_is_desktop_gl() || epoxy_gl_version() < 45) {
        const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
        reason = std::string("context is OpenGL ") + (version ? version : "?") + ", not 4.5 core";
        return false;
    }
    return true;
}

std::string glString(GLenum name)
{
    const char* s = reinterpret_cast<const char*>(glGetString(name));
    return s ? s : "?";
}

} // namespace

struct EglContext::Handles : EglResources
{
};

std::unique_ptr<EglContext> EglContext::create()
{
    checkLibrariesLoadable();

    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!clientExtensions) {
        eglGetError(); // EGL_BAD_DISPLAY without EGL_EXT_client_extensions
    }
    const bool platformBase = hasExtension(clientExtensions, "EGL_EXT_platform_base");

    std::vector<std::string> reasons;
    auto note = [&reasons](const std::string& where, const std::string& reason) {
        reasons.push_back(where + ": " + reason);
    };

    // 1. EGL devices, in order (the NVIDIA path; Mesa lists its devices too).
    int deviceCount = 0;
    if (!platformBase) {
        note("EGL", "EGL_EXT_platform_base not supported (no EGL vendor library found?)");
    } else if (!hasExtension(clientExtensions, "EGL_EXT_device_enumeration") &&
               !hasExtension(clientExtensions, "EGL_EXT_device_base")) {
        note("devices", "EGL_EXT_device_enumeration not supported");
    } else if (!hasExtension(clientExtensions, "EGL_EXT_platform_device")) {
        note("devices", "EGL_EXT_platform_device not supported");
    } else {
        EGLint count = 0;
        if (!eglQueryDevicesEXT(0, nullptr, &count)) {
            note("devices", "eglQueryDevicesEXT failed: " + lastEglError());
        } else if (count > 0) {
            std::vector<EGLDeviceEXT> devices(std::size_t(count), nullptr);
            if (!eglQueryDevicesEXT(count, devices.data(), &count)) {
                note("devices", "eglQueryDevicesEXT failed: " + lastEglError());
                count = 0;
            }
            deviceCount = count;
            for (int i = 0; i < count; ++i) {
                std::string reason;
                EGLDisplay display =
                    eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[std::size_t(i)], nullptr);
                auto handles = std::make_unique<Handles>();
                if (tryDisplay(display, *handles, reason)) {
                    std::unique_ptr<EglContext> context(new EglContext());
                    context->mHandles = std::move(handles);
                    context->mDescription =
                        glString(GL_RENDERER) + " (" + glString(GL_VERSION) + ") via EGL device";
                    return context;
                }
                note("device " + std::to_string(i), reason);
            }
        }
    }

    // 2. Mesa's surfaceless platform (llvmpipe with no /dev/dri at all).
    if (!platformBase) {
        // already noted
    } else if (!hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
        note("surfaceless", "EGL_MESA_platform_surfaceless not supported");
    } else {
        std::string reason;
        EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        auto handles = std::make_unique<Handles>();
        if (tryDisplay(display, *handles, reason)) {
            std::unique_ptr<EglContext> context(new EglContext());
            context->mHandles = std::move(handles);
            context->mDescription = glString(GL_RENDERER) + " (" + glString(GL_VERSION) + ") via EGL surfaceless";
            return context;
        }
        note("surfaceless", reason);
    }

    std::string message = "no EGL display with OpenGL 4.5 core: tried " + std::to_string(deviceCount) + " EGL device" +
                          (deviceCount == 1 ? "" : "s") + " and Mesa surfaceless (";
    for (std::size_t i = 0; i < reasons.size(); ++i) {
        message += (i ? "; " : "") + reasons[i];
    }
    message += "); ";
    message += INSTALL_HINT;
    throw Error(ErrorKind::Gl, message);
}

EglContext::~EglContext() = default;

void EglContext::makeCurrent()
{
    if (eglGetCurrentContext() == mHandles->context) {
        return;
    }
    if (!eglMakeCurrent(mHandles->display, mHandles->surface, mHandles->surface, mHandles->context)) {
        throw Error(ErrorKind::Gl, "cannot make the EGL context current: eglMakeCurrent failed: " + lastEglError());
    }
}

} // namespace strata::render

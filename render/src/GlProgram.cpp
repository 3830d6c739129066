// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "GlProgram.h"

#include <strata/Error.h>
#include <strata/shaders/EmbeddedShaders.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace strata::render::detail {

GlObject createBuffer()
{
    GLuint id = 0;
    glCreateBuffers(1, &id);
    return {id, [](GLuint i) { glDeleteBuffers(1, &i); }};
}

GlObject createVertexArray()
{
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return {id, [](GLuint i) { glDeleteVertexArrays(1, &i); }};
}

GlObject createTexture2D()
{
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    return {id, [](GLuint i) { glDeleteTextures(1, &i); }};
}

GlObject createTexture2DArray()
{
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id);
    return {id, [](GLuint i) { glDeleteTextures(1, &i); }};
}

GlObject createRenderbuffer()
{
    GLuint id = 0;
    glCreateRenderbuffers(1, &id);
    return {id, [](GLuint i) { glDeleteRenderbuffers(1, &i); }};
}

GlObject createFramebuffer()
{
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return {id, [](GLuint i) { glDeleteFramebuffers(1, &i); }};
}

namespace {

std::string glErrorName(GLenum error)
{
    switch (error) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    default: return "GL error " + std::to_string(error);
    }
}

std::size_t digitsEnd(const std::string& s, std::size_t from)
{
    std::size_t end = from;
    while (end < s.size() && s[end] >= '0' && s[end] <= '9') {
        ++end;
    }
    return end;
}

/// Line number (as the GLSL compiler counts them, following #line) → text.
/// Later lines win: the few lines before the first #line share numbers with
/// the prelude, which is where an error is more likely.
std::map<long, std::string> numberedLines(const std::string& source)
{
    std::map<long, std::string> lines;
    long number = 1;
    std::size_t start = 0;
    while (start < source.size()) {
        std::size_t end = source.find('\n', start);
        if (end == std::string::npos) {
            end = source.size();
        }
        const std::string line = source.substr(start, end - start);
        start = end + 1;
        std::size_t first = line.find_first_not_of(" \t");
        if (first != std::string::npos && line.compare(first, 5, "#line") == 0) {
            const std::size_t digits = line.find_first_of("0123456789", first + 5);
            if (digits != std::string::npos) {
                number = std::stol(line.substr(digits, digitsEnd(line, digits) - digits));
                continue;
            }
        }
        lines[number] = line;
        ++number;
    }
    return lines;
}

std::string trimmed(const std::string& s)
{
    const std::size_t first = s.find_first_not_of(" \t\r");
    if (first == std::string::npos) {
        return "";
    }
    const std::size_t last = s.find_last_not_of(" \t\r");
    return s.substr(first, last - first + 1);
}

std::string readLog(GLuint id, bool program)
{
    GLint length = 0;
    if (program) {
        glGetProgramiv(id, GL_INFO_LOG_LENGTH, &length);
    } else {
        glGetShaderiv(id, GL_INFO_LOG_LENGTH, &length);
    }
    std::string log(std::size_t(std::max(length, 1)), '\0');
    if (program) {
        glGetProgramInfoLog(id, GLsizei(log.size()), nullptr, log.data());
    } else {
        glGetShaderInfoLog(id, GLsizei(log.size()), nullptr, log.data());
    }
    log.resize(std::strlen(log.c_str()));
    return log;
}

} // namespace

void checkGl(const char* what)
{
    GLenum error = glGetError();
    if (error == GL_NO_ERROR) {
        return;
    }
    std::string names = glErrorName(error);
    // Drain the queue (bounded: a lost context may report forever).
    for (int i = 0; i < 8 && (error = glGetError()) != GL_NO_ERROR; ++i) {
        names += ", " + glErrorName(error);
    }
    throw Error(ErrorKind::Gl, "OpenGL error while " + std::string(what) + ": " + names);
}

void clearGlErrors()
{
    for (int i = 0; i < 64 && glGetError() != GL_NO_ERROR; ++i) {
    }
}

std::string describeShaderLog(const std::string& log, const std::string& source)
{
    const std::map<long, std::string> sourceLines = numberedLines(source);
    std::vector<std::string> errors;
    std::vector<std::string> others;
    std::size_t start = 0;
    while (start < log.size()) {
        std::size_t end = log.find('\n', start);
        if (end == std::string::npos) {
            end = log.size();
        }
        std::string line = log.substr(start, end - start);
        start = end + 1;
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) {
            line.pop_back();
        }
        if (line.empty()) {
            continue;
        }
        std::string quoted;
        const std::size_t stringEnd = digitsEnd(line, 0);
        if (stringEnd > 0 && stringEnd + 1 < line.size() && (line[stringEnd] == ':' || line[stringEnd] == '(')) {
            const std::size_t lineEnd = digitsEnd(line, stringEnd + 1);
            if (lineEnd > stringEnd + 1 && lineEnd - stringEnd < 10) {
                const long number = std::stol(line.substr(stringEnd + 1, lineEnd - stringEnd - 1));
                const auto found = sourceLines.find(number);
                if (found != sourceLines.end()) {
                    quoted = trimmed(found->second);
                }
                const auto file = std::size_t(number / shaders::SOURCE_LINE_BASE);
                if (file < shaders::SOURCE_NAME_COUNT) {
                    line = shaders::SOURCE_NAMES[file] + line.substr(stringEnd, 1) +
                           std::to_string(number % shaders::SOURCE_LINE_BASE) + line.substr(lineEnd);
                }
            }
        }
        if (!quoted.empty()) {
            line += " `" + quoted + "`";
        }
        (line.find("error") != std::string::npos ? errors : others).push_back(line);
    }
    // Errors only, when there are any: the warnings that follow them are noise.
    std::string out;
    for (const std::string& line : errors.empty() ? others : errors) {
        out += (out.empty() ? "" : " | ") + line;
    }
    return out.empty() ? "(empty log)" : out;
}

GlObject compileShader(GLenum stage, const std::string& source, const std::string& name)
{
    const GLuint id = glCreateShader(stage);
    GlObject shader(id, [](GLuint i) { glDeleteShader(i); });
    const char* text = source.c_str();
    glShaderSource(id, 1, &text, nullptr);
    glCompileShader(id);
    GLint ok = GL_FALSE;
    glGetShaderiv(id, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        throw Error(ErrorKind::Gl, "GLSL compile error in the " + name + " shader: " + describeShaderLog(readLog(id, false), source));
    }
    return shader;
}

GlObject linkProgram(const GlObject& vertex, const GlObject& fragment, const std::string& name)
{
    const GLuint id = glCreateProgram();
    GlObject program(id, [](GLuint i) { glDeleteProgram(i); });
    glAttachShader(id, vertex.id());
    glAttachShader(id, fragment.id());
    glLinkProgram(id);
    GLint ok = GL_FALSE;
    glGetProgramiv(id, GL_LINK_STATUS, &ok);
    if (!ok) {
        throw Error(ErrorKind::Gl, "GLSL link error in the " + name + " program: " + describeShaderLog(readLog(id, true), ""));
    }
    glDetachShader(id, vertex.id());
    glDetachShader(id, fragment.id());
    return program;
}

} // namespace strata::render::detail

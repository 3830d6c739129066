// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "ImageOutputFile.h"

#include <strata/AtomicFile.h>
#include <strata/Error.h>

#include <OpenImageIO/filesystem.h>

#include <algorithm>
#include <vector>

namespace strata::render::detail {

std::string oiioErrorLine(const std::string& objectError)
{
    std::string message = objectError.empty() ? OIIO::geterror() : objectError;
    while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
    std::replace(message.begin(), message.end(), '\n', ' ');
    return message.empty() ? "unknown OpenImageIO error" : message;
}

void writeImageFile(const std::filesystem::path& path,
                    const std::function<void(OIIO::ImageOutput& output, const std::string& name)>& encode)
{
    const auto noWriter = [&]() {
        return Error(ErrorKind::Io, "cannot write image '" + path.string() + "': " + oiioErrorLine({}),
                     {.file = path.string()});
    };
    auto output = OIIO::ImageOutput::create(path.string());
    if (!output) throw noWriter();
    // Only formats whose memory output was checked to give the same file:
    // OpenImageIO 2.4's TIFF writer produces a broken file through a proxy.
    const std::string format = output->format_name();
    if ((format == "png" || format == "openexr") && output->supports("ioproxy")) {
        std::vector<unsigned char> bytes;
        OIIO::Filesystem::IOVecOutput proxy(bytes);
        if (output->set_ioproxy(&proxy)) {
            encode(*output, path.string());
            writeFileAtomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
            return;
        }
    }
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        auto fileOutput = OIIO::ImageOutput::create(temporary.string());
        if (!fileOutput) throw noWriter();
        encode(*fileOutput, temporary.string());
    });
}

} // namespace strata::render::detail

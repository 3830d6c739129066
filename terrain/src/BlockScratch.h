// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Scratch arrays for block evaluation without a heap allocation per call:
/// one stack of memory per thread, from which a node's densities() takes the
/// arrays it needs (a ScratchFrame) and to which they return when it does.
/// Nodes nest (a warp calls a terrace calls a heightfield), and so do their
/// frames, like the calls themselves. The sampler evaluates millions of small
/// blocks; a malloc and free per node and block cost about a tenth of it.

#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace strata::terrain::detail {

/// The arrays taken through one frame, valid until it is destroyed. Frames
/// must end in the reverse order of their creation on a thread (automatic
/// variables do), and an array must not be handed to another thread.
class ScratchFrame
{
public:
    ScratchFrame();
    ~ScratchFrame();
    ScratchFrame(const ScratchFrame&) = delete;
    ScratchFrame& operator=(const ScratchFrame&) = delete;

    /// n uninitialised values of a trivial type (64-byte aligned).
    template <class T>
    T* array(std::size_t n)
    {
        static_assert(std::is_trivial_v<T>);
        return static_cast<T*>(take(n * sizeof(T)));
    }

private:
    void* take(std::size_t bytes);
    std::size_t mChunk;  ///< the thread's chunk in use when the frame began
    std::size_t mOffset; ///< and its fill
};

} // namespace strata::terrain::detail

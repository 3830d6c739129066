// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "BlockScratch.h"

#include <algorithm>
#include <memory>
#include <new>
#include <vector>

namespace strata::terrain::detail {

namespace {

constexpr std::size_t ALIGN = 64;
/// A chunk holds the arrays of several nested nodes on 8³ blocks (a warp
/// takes 6 × 512 doubles, 24 KiB); larger requests get a chunk of their own.
constexpr std::size_t CHUNK_BYTES = std::size_t(256) << 10;

struct Chunk
{
    std::unique_ptr<std::byte[]> memory;
    std::size_t size = 0;
    std::byte* begin() const
    {
        // The first ALIGN-aligned byte: the allocation has ALIGN bytes spare.
        const auto at = reinterpret_cast<std::uintptr_t>(memory.get());
        return memory.get() + ((ALIGN - at % ALIGN) % ALIGN);
    }
};

/// One thread's stack: chunks in order, the one in use and its fill. Chunks
/// are kept once made (a thread's deepest nesting sizes them), and only the
/// offsets move, so taking an array is a few additions.
struct Stack
{
    std::vector<Chunk> chunks;
    std::size_t chunk = 0;
    std::size_t offset = 0;
};

thread_local Stack tStack;

} // namespace

ScratchFrame::ScratchFrame()
    : mChunk(tStack.chunk), mOffset(tStack.offset)
{
}

ScratchFrame::~ScratchFrame()
{
    tStack.chunk = mChunk;
    tStack.offset = mOffset;
}

void* ScratchFrame::take(std::size_t bytes)
{
    Stack& s = tStack;
    bytes = (bytes + ALIGN - 1) / ALIGN * ALIGN;
    // Move on to the next chunk (making or growing it) until one has room.
    while (s.chunk >= s.chunks.size() || s.offset + bytes > s.chunks[s.chunk].size) {
        if (s.chunk < s.chunks.size() && s.offset > 0) {
            ++s.chunk;
            s.offset = 0;
            continue;
        }
        // An empty chunk at s.chunk that is too small, or none: (re)make it.
        // Only a chunk this frame's stack has not used yet is replaced.
        const std::size_t size = std::max(CHUNK_BYTES, bytes);
        Chunk made{std::make_unique_for_overwrite<std::byte[]>(size + ALIGN), size};
        if (s.chunk < s.chunks.size()) s.chunks[s.chunk] = std::move(made);
        else s.chunks.push_back(std::move(made));
    }
    std::byte* at = s.chunks[s.chunk].begin() + s.offset;
    s.offset += bytes;
    return at;
}

} // namespace strata::terrain::detail

// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal (for Strata's libraries, not for users): tells ThreadSanitizer
// about a happens-before edge that TBB
// provides but TSan cannot see (TBB is not built with TSan here, so its
// internal atomics are invisible to it). Everything a thread does before
// tbb::task_arena::enqueue() or tbb::parallel_for() happens before the task
// or body runs, and a parallel_for's bodies happen before it returns: TBB
// guarantees both. These annotations only describe those edges to TSan;
// they compile to nothing in other builds (no lock on the hot path).
//
// One edge cannot be described by a release/acquire pair: a task's closure
// is copied into TBB's task memory inside enqueue(), after anything the
// enqueuing thread can release, so the task's read of its own capture looks
// unordered to TSan. tsanUncheckedRead() reads such a capture with TSan's
// read checks off for that one load.

#if defined(__SANITIZE_THREAD__)
#define STRATA_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define STRATA_TSAN 1
#endif
#endif

#ifdef STRATA_TSAN
#include <sanitizer/tsan_interface.h>
// TSan's dynamic annotations (tsan_interface_ann.cpp); no public header declares them.
extern "C" void AnnotateIgnoreReadsBegin(const char* file, int line);
extern "C" void AnnotateIgnoreReadsEnd(const char* file, int line);
#endif

namespace strata::detail {

/// Before handing work to TBB: what this thread did so far is published
/// under `key` (any address both sides agree on).
inline void tsanHandOff(const void* key)
{
#ifdef STRATA_TSAN
    __tsan_release(const_cast<void*>(key));
#else
    (void)key;
#endif
}

/// First thing in the task or body (or after the parallel_for, for what its
/// bodies published): takes what was published under `key`.
inline void tsanTakeOver(const void* key)
{
#ifdef STRATA_TSAN
    __tsan_acquire(const_cast<void*>(key));
#else
    (void)key;
#endif
}

/// A copy of `value`, a capture of a TBB task's closure (which TBB wrote
/// into its own task memory and handed over with its own synchronisation),
/// read without TSan checking that one load.
template<typename T>
T tsanUncheckedRead(const T& value)
{
#ifdef STRATA_TSAN
    AnnotateIgnoreReadsBegin(__FILE__, __LINE__);
    const T copy = value;
    AnnotateIgnoreReadsEnd(__FILE__, __LINE__);
    return copy;
#else
    return value;
#endif
}

} // namespace strata::detail

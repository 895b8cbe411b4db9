#pragma once
// A vector for large build scratch arrays of plain numbers that parallel loops fill: resizing
// leaves new elements uninitialised instead of zeroing them on one thread, so each page is first
// written (and faulted in) by the thread that fills it. LargeScratchVector also maps blocks of
// 2 MiB or more as huge pages (base/large_pages.h): one fault per 2 MiB instead of per 4 KiB.

#include "base/large_pages.h"

#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace rtlab {

/// Base (std::allocator by default) that default-initialises where a vector value-initialises
/// (no zeroing).
template <class T, class Base = std::allocator<T>>
struct UninitAllocator : Base {
    UninitAllocator() = default;
    template <class U, class B>
    UninitAllocator(const UninitAllocator<U, B>&) noexcept {}  // NOLINT: rebinding

    template <class U>
    struct rebind {
        using other =
            UninitAllocator<U, typename std::allocator_traits<Base>::template rebind_alloc<U>>;
    };

    /// Default-initialises: an arithmetic U keeps whatever the memory held.
    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

/// A vector of trivial T whose resize and size constructor leave the elements unset: every
/// element must be written before it is read.
template <class T>
requires std::is_trivially_default_constructible_v<T>
using ScratchVector = std::vector<T, UninitAllocator<T>>;

/// A ScratchVector whose storage, once 2 MiB or more, sits in huge pages.
template <class T>
requires std::is_trivially_default_constructible_v<T>
using LargeScratchVector = std::vector<T, UninitAllocator<T, LargePageAllocator<T>>>;

}  // namespace rtlab

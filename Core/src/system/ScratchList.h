// The lists of one insertion's scratch (the cavity, its boundary, the fill's tables) are resized
// at every insertion, to sizes that go up and down with the cavities. std::vector's resize()
// value-initializes what it adds (zeros written only to be overwritten) and, even with an
// allocator that leaves elements uninitialized, calls out of line whenever the size goes up: a
// few percent of a whole insertion. Here resize() is a comparison and a store, and the room only
// grows.
#ifndef fd3_ScratchList_h
#define fd3_ScratchList_h

#include <algorithm>
#include <cstddef>
#include <memory>
#include <type_traits>
#include <utility>

namespace fd3
{

/// A list of plain items whose new ones are left uninitialized, with room that only grows (until
/// the list is replaced by an empty one).
template <typename T>
class ScratchList
{
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_default_constructible_v<T>,
    "a ScratchList holds plain items, copied as bytes and never initialized");

public:
  ScratchList() = default;
  /// The moved-from list is left empty, as a std::vector is.
  ScratchList(ScratchList&& other) noexcept { *this = std::move(other); }
  ScratchList& operator=(ScratchList&& other) noexcept
  {
    items_ = std::move(other.items_);
    size_ = std::exchange(other.size_, 0);
    capacity_ = std::exchange(other.capacity_, 0);
    return *this;
  }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  std::size_t capacity() const { return capacity_; }
  T* data() { return items_.get(); }
  const T* data() const { return items_.get(); }
  T& operator[](std::size_t i) { return items_[i]; }
  const T& operator[](std::size_t i) const { return items_[i]; }
  T* begin() { return data(); }
  T* end() { return data() + size_; }
  const T* begin() const { return data(); }
  const T* end() const { return data() + size_; }
  T& back() { return items_[size_ - 1]; }

  /// The items beyond the old size hold whatever their room held: nothing written, or earlier
  /// items.
  void resize(std::size_t size)
  {
    if (size > capacity_)
      grow(size);
    size_ = size;
  }
  void clear() { size_ = 0; }
  void push_back(const T& item)
  {
    const T copy = item; // it may be one of the items, which grow() moves
    if (size_ == capacity_)
      grow(size_ + 1);
    items_[size_++] = copy;
  }

private:
  /// Room for `size` items or more: at least half as much again as before, so that pushing back
  /// one at a time copies each item a bounded number of times.
  void grow(std::size_t size)
  {
    const std::size_t capacity = std::max({size, capacity_ + capacity_ / 2, std::size_t(16)});
    std::unique_ptr<T[]> items(new T[capacity]); // default-initialized: not written
    std::copy(begin(), end(), items.get());
    items_ = std::move(items);
    capacity_ = capacity;
  }

  std::unique_ptr<T[]> items_;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

} // namespace fd3

#endif

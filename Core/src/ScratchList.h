// A list reused by every insertion: it keeps its storage, so the steady state allocates nothing,
// and pushIf() appends without a branch on its condition. That matters in the cavity search,
// where conditions are the outcomes of insphere tests: a coin toss to the branch predictor, whose
// misses would serialize tests that can otherwise overlap.
#ifndef fd3_ScratchList_h
#define fd3_ScratchList_h

#include <cstddef>
#include <vector>

namespace fd3
{

template <typename T>
class ScratchList
{
public:
  std::size_t size() const { return size_; }
  void clear() { size_ = 0; }
  T& operator[](std::size_t i) { return items_[i]; }
  const T& operator[](std::size_t i) const { return items_[i]; }
  T* begin() { return items_.data(); }
  T* end() { return items_.data() + size_; }
  const T* begin() const { return items_.data(); }
  const T* end() const { return items_.data() + size_; }
  const T& back() const { return items_[size_ - 1]; }

  /// Room for `count` more items, so that as many pushIf() calls need no check.
  void reserveMore(std::size_t count)
  {
    if (size_ + count > items_.size())
      items_.resize(2 * (size_ + count));
  }
  /// Writes x past the end and keeps it only when `keep` holds; needs room (reserveMore).
  void pushIf(bool keep, const T& x)
  {
    items_[size_] = x;
    size_ += keep;
  }
  void push_back(const T& x)
  {
    reserveMore(1);
    items_[size_++] = x;
  }
  template <typename Predicate>
  void removeIf(Predicate remove)
  {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < size_; ++i)
      if (!remove(items_[i]))
        items_[kept++] = items_[i];
    size_ = kept;
  }
  void release()
  {
    std::vector<T>().swap(items_);
    size_ = 0;
  }

private:
  std::vector<T> items_;
  std::size_t size_ = 0;
};

} // namespace fd3

#endif

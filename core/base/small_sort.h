#pragma once
// A stable sort for the many short runs hot loops sort one after another (a stencil row's terms,
// one vertex's half-edges): insertion sort up to 32 elements, which allocates no buffer and
// takes a handful of compares; std::stable_sort above, so a long run stays n log n.
#include <algorithm>
#include <iterator>
#include <utility>

namespace sublift {

template <class It, class Less>
void stable_sort_small(It first, It last, Less less) {
  if (std::distance(first, last) > 32) {
    std::stable_sort(first, last, less);
    return;
  }
  if (first == last) return;
  for (It i = std::next(first); i != last; ++i)
    for (It j = i; j != first && less(*j, *std::prev(j)); --j) std::iter_swap(j, std::prev(j));
}

}  // namespace sublift

// KLU analysis with the column singletons first (klu_singleton_analysis.hpp).
#include "klu_singleton_analysis.hpp"

#include <algorithm>
#include <cstddef>

namespace lcprelax::sparse::detail {
namespace {

// Allocation as KLU's own (KLU_malloc: SuiteSparse_malloc, counted in common's memusage),
// so that klu_free_symbolic releases it and keeps the count.
template <class T>
T* klu_style_alloc(std::size_t count, klu_common* common) {
  const std::size_t items = std::max<std::size_t>(count, 1);
  T* p = static_cast<T*>(SuiteSparse_malloc(items, sizeof(T)));
  if (!p) {
    common->status = KLU_OUT_OF_MEMORY;
    return nullptr;
  }
  common->memusage += items * sizeof(T);
  common->mempeak = std::max(common->mempeak, common->memusage);
  return p;
}

// The symbolic object of an n×n matrix, fields zeroed, P, Q, R and Lnz allocated; nullptr
// (status set) when out of memory.
klu_symbolic* new_symbolic(int n, klu_common* common) {
  klu_symbolic* s = klu_style_alloc<klu_symbolic>(1, common);
  if (!s) return nullptr;
  *s = klu_symbolic{};
  s->n = n;
  s->P = klu_style_alloc<int>(static_cast<std::size_t>(n), common);
  s->Q = klu_style_alloc<int>(static_cast<std::size_t>(n), common);
  s->R = klu_style_alloc<int>(static_cast<std::size_t>(n) + 1, common);
  s->Lnz = klu_style_alloc<double>(static_cast<std::size_t>(n), common);
  if (!s->P || !s->Q || !s->R || !s->Lnz) {
    klu_free_symbolic(&s, common);
    common->status = KLU_OUT_OF_MEMORY;
    return nullptr;
  }
  return s;
}

}  // namespace

klu_symbolic* analyze_singletons_first(int n, const int* Ap, const int* Ai, klu_common* common,
                                       SingletonAnalysisWork& w, int& peeled) {
  peeled = 0;
  if (n <= 0 || !common->btf || (common->ordering != 0 && common->ordering != 1)) return nullptr;
  const auto N = static_cast<std::size_t>(n);
  // Column singletons, each on a row of its own: their rows are marked −1 in reduced_row,
  // then the other rows are numbered in order (the row map is increasing, so sorted
  // columns stay sorted in K).
  w.reduced_row.assign(N, 0);
  int s = 0;
  for (int j = 0; j < n; ++j) {
    if (Ap[j + 1] - Ap[j] != 1) continue;
    const int i = Ai[Ap[j]];
    if (i < 0 || i >= n || w.reduced_row[static_cast<std::size_t>(i)] < 0) return nullptr;
    w.reduced_row[static_cast<std::size_t>(i)] = -1;
    ++s;
  }
  if (s == 0) return nullptr;
  // K: the rows without a singleton and the columns that are not singletons, in A's order.
  const int m = n - s;
  w.kept_row.clear();
  w.kept_col.clear();
  for (int i = 0; i < n; ++i)
    if (w.reduced_row[static_cast<std::size_t>(i)] == 0) {
      w.reduced_row[static_cast<std::size_t>(i)] = static_cast<int>(w.kept_row.size());
      w.kept_row.push_back(i);
    }
  w.Kp.resize(static_cast<std::size_t>(m) + 1);
  w.Ki.resize(std::max<std::size_t>(static_cast<std::size_t>(Ap[n]), 1));
  int c = 0, e = 0;
  w.Kp[0] = 0;
  for (int j = 0; j < n; ++j) {
    if (Ap[j + 1] - Ap[j] == 1) continue;
    w.kept_col.push_back(j);
    int previous = -1;
    for (int p = Ap[j]; p < Ap[j + 1]; ++p) {
      const int i = Ai[p];
      if (i <= previous || i >= n) return nullptr;  // unsorted, repeated or out of range
      previous = i;
      // Kept or not without a branch (about half of a Lemke basis' entries are in slack
      // rows, in no predictable order): the slot is overwritten when the row is not kept.
      const int r = w.reduced_row[static_cast<std::size_t>(i)];
      w.Ki[static_cast<std::size_t>(e)] = r;
      e += r >= 0;
    }
    w.Kp[static_cast<std::size_t>(++c)] = e;
  }
  klu_symbolic* sk = nullptr;
  if (m > 0) {
    sk = klu_analyze(m, w.Kp.data(), w.Ki.data(), common);
    if (!sk) return nullptr;  // common->status says why; the caller's klu_analyze reports it
    if (sk->structural_rank < m) {
      klu_free_symbolic(&sk, common);
      return nullptr;
    }
  }
  klu_symbolic* a = new_symbolic(n, common);
  if (!a) {
    if (sk) klu_free_symbolic(&sk, common);
    return nullptr;
  }
  // Leading 1×1 blocks: the singletons in column order (natural ordering; Lnz 1 as KLU
  // counts a block of size 1), then K's blocks with its permutations mapped back to A.
  int k = 0;
  for (int j = 0; j < n; ++j) {
    if (Ap[j + 1] - Ap[j] != 1) continue;
    a->P[k] = Ai[Ap[j]];
    a->Q[k] = j;
    a->R[k] = k;
    a->Lnz[k] = 1.0;
    ++k;
  }
  a->nz = Ap[n];
  a->ordering = common->ordering;
  a->do_btf = 1;
  a->structural_rank = n;
  if (sk) {
    for (int t = 0; t < m; ++t) {
      a->P[s + t] = w.kept_row[static_cast<std::size_t>(sk->P[t])];
      a->Q[s + t] = w.kept_col[static_cast<std::size_t>(sk->Q[t])];
    }
    for (int b = 0; b <= sk->nblocks; ++b) a->R[s + b] = s + sk->R[b];
    for (int b = 0; b < sk->nblocks; ++b) a->Lnz[s + b] = sk->Lnz[b];
    a->nblocks = s + sk->nblocks;
    a->maxblock = std::max(1, sk->maxblock);
    // Off-diagonal entries: K's own, and every entry of K's columns in a singleton's row.
    const int k_entries = w.Kp[static_cast<std::size_t>(m)];
    a->nzoff = sk->nzoff + (Ap[n] - s - k_entries);
    a->symmetry = sk->symmetry;
    a->est_flops = sk->est_flops;
    a->lnz = sk->lnz < 0 ? sk->lnz : sk->lnz + s;
    a->unz = sk->unz < 0 ? sk->unz : sk->unz + s;
    klu_free_symbolic(&sk, common);
  } else {
    a->R[n] = n;
    a->nblocks = n;
    a->maxblock = 1;
    a->nzoff = 0;
    a->symmetry = 1.0;
    a->est_flops = 0.0;
    a->lnz = a->unz = n;
  }
  common->status = KLU_OK;
  common->structural_rank = n;
  peeled = s;
  return a;
}

}  // namespace lcprelax::sparse::detail

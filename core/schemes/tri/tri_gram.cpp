#include "core/schemes/tri/tri_gram.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <unordered_map>

#include "core/base/errors.h"
#include "core/base/parallel.h"
#include "core/complex/refine_tri.h"
#include "core/schemes/registry.h"

namespace sublift {

TriGramRadii tri_gram_radii(Scheme s) {
  // support: N(f) must hold every function that is non-zero on f and close under one step
  // (checked when a type is built). signature >= support + 2 decides the stencils of N(child)
  // and the children's own signatures; patch >= signature + 1 keeps the copied fans complete
  // out to where one subdivided step still reads them.
  switch (s) {
    case Scheme::LinearTri: return {0, 2, 4};
    case Scheme::Loop: return {1, 3, 4};
    case Scheme::Butterfly: return {3, 5, 6};
    default: throw Error(scheme_name(s) + " is not a triangle scheme");
  }
}

FaceGramCache::FaceGramCache(Scheme s) : scheme_(s), radii_(tri_gram_radii(s)) {}

void face_seeds(const Complex& c, std::uint32_t f, std::uint32_t seeds[3], std::uint32_t starts[3]) {
  const std::uint32_t b = c.faces.offsets[f];
  for (int k = 0; k < 3; ++k) {
    seeds[k] = c.faces.items[b + k];
    starts[k] = c.faces.items[b + (k + 1) % 3];
  }
}

// A new type's patch subdivided, kept while the children read there are made.
struct FaceGramCache::Made {
  int n = 0;
  std::array<Eigen::SparseMatrix<double>, 4> S;
  std::array<std::string, 4> child_sig;
  std::array<LocalOrder, 4> child_order;
  struct Refined {
    Complex fine;
    TriRings rings;
  };
  std::shared_ptr<const Refined> refined;
  std::uint32_t pf = 0;  // the face in the patch; its children are 4 pf + k of `fine`
};

FaceGramCache::Made FaceGramCache::make_type(const Complex& c, const TriRings& r, const LocalOrder& order,
                                             std::uint32_t f) const {
  Made made;
  const int n = static_cast<int>(labels_within(order, radii_.support));
  made.n = n;
  // Subdivide a copy of the neighbourhood once; the face is the patch face on labels 0, 1, 2.
  const Complex patch = local_patch(c, r, order);
  std::uint32_t pf = UINT32_MAX;
  for (std::uint32_t g = 0; g < patch.num_faces() && pf == UINT32_MAX; ++g) {
    const auto row = patch.faces.row(g);
    if (row[0] < 3 && row[1] < 3 && row[2] < 3) pf = g;
  }
  if (pf == UINT32_MAX) throw std::logic_error("tri_gram: the face is missing from its own patch");
  auto refined = std::make_shared<Made::Refined>();
  std::optional<TriRowRules> rules;
  try {
    refined->fine = refine_tri(patch, false);  // its rings serve its children (local_patch)
    rules.emplace(patch, scheme_);
    // The patch's rings, then the refined patch's from them (a quarter of the searching).
    refined->rings = refine_tri_rings(patch, build_tri_rings(patch));
  } catch (const TopologyError& e) {
    // local_patch always yields a manifold (it splits rim vertices where the surface meets
    // itself), so this is a defect.
    throw std::logic_error("tri_gram: the patch around face " + std::to_string(f) + " cannot be subdivided: " + e.what());
  }
  // Only the rows of N(child) are read, about a tenth of the patch's: made when first asked.
  thread_local std::vector<std::uint32_t> row_of;
  thread_local Csr rows;
  thread_local std::vector<double> weights;
  row_of.assign(refined->fine.num_vertices, UINT32_MAX);
  rows.clear();
  weights.clear();
  for (int k = 0; k < 4; ++k) {
    LocalOrder& co = made.child_order[static_cast<std::size_t>(k)];
    std::uint32_t seeds[3], starts[3];
    face_seeds(refined->fine, 4 * pf + static_cast<std::uint32_t>(k), seeds, starts);
    local_order(refined->rings, seeds, starts, radii_.patch, co);
    made.child_sig[static_cast<std::size_t>(k)] = local_signature(refined->fine, refined->rings, co, radii_.signature);
    const int m = static_cast<int>(labels_within(co, radii_.support));
    std::vector<Eigen::Triplet<double>> terms;
    for (int i = 0; i < m; ++i) {
      const std::uint32_t v = co.vertex[static_cast<std::size_t>(i)];
      const auto add = [&](std::uint32_t a, double w) {
        if (a >= static_cast<std::uint32_t>(n))
          throw std::logic_error("tri_gram: N(f) does not close under subdivision (support radius too small)");
        terms.emplace_back(i, static_cast<int>(a), w);
      };
      if (row_of[v] == UINT32_MAX) {
        row_of[v] = static_cast<std::uint32_t>(rows.rows());
        rules->append_row(v, rows, weights);
      }
      for (std::uint32_t q = rows.offsets[row_of[v]]; q < rows.offsets[row_of[v] + 1]; ++q) add(rows.items[q], weights[q]);
    }
    Eigen::SparseMatrix<double> S(m, n);
    S.setFromTriplets(terms.begin(), terms.end());  // repeated (i, a) summed, as += did
    made.S[static_cast<std::size_t>(k)] = std::move(S);
  }
  made.refined = std::move(refined);
  made.pf = pf;
  return made;
}

void FaceGramCache::add_types(std::span<const FaceRef> faces) {
  // A face whose type is asked: its order and signature once known (children come with theirs);
  // `keep` holds the subdivided patch a child lies in.
  struct Request {
    FaceRef at;
    std::shared_ptr<const Made::Refined> keep;
    bool known = false;
    std::string sig;
    LocalOrder order;
  };
  // Chunks of faces bound the patches kept at once (a wave's children hold their parents').
  constexpr std::size_t kChunk = 256;
  for (std::size_t c0 = 0; c0 < faces.size(); c0 += kChunk) {
    const std::size_t first_type = types_.size();
    std::vector<std::string> claimed;
    std::vector<std::pair<int, std::array<std::string, 4>>> children;  // a new type's child signatures
    std::vector<Request> wave;
    for (std::size_t i = c0; i < std::min(faces.size(), c0 + kChunk); ++i) {
      Request q;
      q.at = faces[i];
      wave.push_back(std::move(q));
    }
    try {
      while (!wave.empty()) {
        const auto nw = static_cast<std::uint32_t>(wave.size());
        std::exception_ptr fault;
        std::mutex fault_mutex;
        const auto keep_fault = [&] {  // a pool task must not throw: the first fault is rethrown
          const std::lock_guard<std::mutex> lock(fault_mutex);
          if (!fault) fault = std::current_exception();
        };
        parallel_for(nw, 16, [&](std::uint32_t b, std::uint32_t e) {
          try {
            for (std::uint32_t i = b; i < e; ++i) {
              Request& q = wave[i];
              if (q.known) continue;
              std::uint32_t seeds[3], starts[3];
              face_seeds(*q.at.mesh, q.at.face, seeds, starts);
              local_order(*q.at.rings, seeds, starts, radii_.patch, q.order);
              q.sig = local_signature(*q.at.mesh, *q.at.rings, q.order, radii_.signature);
              q.known = true;
            }
          } catch (...) {
            keep_fault();
          }
        });
        if (fault) std::rethrow_exception(fault);
        // Numbered in wave order: the first request of each new signature makes it.
        std::vector<std::uint32_t> fresh;
        std::vector<int> fresh_id;
        for (std::uint32_t i = 0; i < nw; ++i) {
          const auto [it, inserted] = index_.try_emplace(wave[i].sig, static_cast<int>(types_.size()));
          if (!inserted) continue;
          claimed.push_back(wave[i].sig);
          fresh.push_back(i);
          fresh_id.push_back(it->second);
          types_.emplace_back();
          signature_.push_back(&it->first);  // keys of an unordered_map stay where they are
          pending_.push_back(it->second);
        }
        std::vector<Made> made(fresh.size());
        parallel_for(static_cast<std::uint32_t>(fresh.size()), 4, [&](std::uint32_t b, std::uint32_t e) {
          try {
            for (std::uint32_t k = b; k < e; ++k) {
              const Request& q = wave[fresh[k]];
              made[k] = make_type(*q.at.mesh, *q.at.rings, q.order, q.at.face);
            }
          } catch (...) {
            keep_fault();
          }
        });
        if (fault) std::rethrow_exception(fault);
        std::vector<Request> next;
        for (std::size_t k = 0; k < made.size(); ++k) {
          Made& m = made[k];
          Type& t = types_[static_cast<std::size_t>(fresh_id[k])];
          t.n = m.n;
          t.S = std::move(m.S);
          children.emplace_back(fresh_id[k], m.child_sig);
          for (std::size_t j = 0; j < 4; ++j)
            if (!index_.count(m.child_sig[j]))
              next.push_back({{&m.refined->fine, &m.refined->rings, 4 * m.pf + static_cast<std::uint32_t>(j)},
                              m.refined, true, std::move(m.child_sig[j]), std::move(m.child_order[j])});
        }
        wave = std::move(next);
      }
    } catch (...) {
      // A defect (see make_type); the cache is kept across calls: forget the chunk's half-made types.
      for (const std::string& sig : claimed) index_.erase(sig);
      types_.resize(first_type);
      signature_.resize(first_type);
      pending_.erase(std::remove_if(pending_.begin(), pending_.end(), [&](int t) { return t >= static_cast<int>(first_type); }),
                     pending_.end());
      throw;
    }
    for (const auto& [id, sigs] : children)
      for (std::size_t j = 0; j < 4; ++j) types_[static_cast<std::size_t>(id)].child[j] = index_.at(sigs[j]);
    solve_pending();
  }
}

void FaceGramCache::solve_pending() {
  // Most new types depend on others without a cycle (faces near several extraordinary vertices
  // or features, which become simpler under subdivision): they are evaluated once, children
  // first. Only the strongly connected parts (self-similar corners, the regular type) need
  // sweeps. Tarjan's algorithm yields the components children first.
  const auto eval = [&](int t) {
    Type& ty = types_[static_cast<std::size_t>(t)];
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(ty.n, ty.n);
    for (int k = 0; k < 4; ++k) {
      const Eigen::SparseMatrix<double>& S = ty.S[static_cast<std::size_t>(k)];
      const Eigen::MatrixXd GS = types_[static_cast<std::size_t>(ty.child[static_cast<std::size_t>(k)])].G * S;
      G.noalias() += S.transpose() * GS;
    }
    G *= 0.25;
    // Through a temporary: written in place, `G = 0.5 * (G + G.transpose())` reads entries it
    // has already overwritten (Eigen assumes no aliasing there) and left G(i, j) != G(j, i).
    const Eigen::MatrixXd Gt = G.transpose();
    G = 0.5 * (G + Gt);
    G /= G.sum();  // the functions sum to 1 on the face: entries sum to its area
    const double change = (G - ty.G).cwiseAbs().maxCoeff();
    ty.G = std::move(G);
    return change;
  };
  std::unordered_map<int, int> index, low;
  std::vector<int> stack;
  std::unordered_map<int, bool> on_stack;
  int counter = 0;
  last_change_ = 0;
  std::function<void(int)> visit = [&](int t) {
    index[t] = low[t] = counter++;
    stack.push_back(t);
    on_stack[t] = true;
    for (int c : types_[static_cast<std::size_t>(t)].child) {
      if (types_[static_cast<std::size_t>(c)].solved) continue;
      if (!index.count(c)) {
        visit(c);
        low[t] = std::min(low[t], low[c]);
      } else if (on_stack[c]) {
        low[t] = std::min(low[t], index[c]);
      }
    }
    if (low[t] != index[t]) return;
    std::vector<int> comp;
    int x;
    do {
      x = stack.back();
      stack.pop_back();
      on_stack[x] = false;
      comp.push_back(x);
    } while (x != t);
    for (int y : comp) {
      Type& ty = types_[static_cast<std::size_t>(y)];
      ty.G = Eigen::MatrixXd::Constant(ty.n, ty.n, 1.0 / (double(ty.n) * ty.n));
    }
    bool cyclic = comp.size() > 1;
    for (int c : types_[static_cast<std::size_t>(t)].child) cyclic |= c == t;
    if (!cyclic) {
      eval(t);
    } else {
      // Swept in the order of the types' signatures, not of their numbers: a component's values
      // then depend on it alone, not on which face led to it first.
      std::sort(comp.begin(), comp.end(), [&](int a, int b) { return *signature_[static_cast<std::size_t>(a)] < *signature_[static_cast<std::size_t>(b)]; });
      double prev = 1e300;
      for (int sweep = 0; sweep < 400; ++sweep) {
        double change = 0;
        for (int y : comp) change = std::max(change, eval(y));
        // Converged to rounding: the change stops shrinking once it is a few ulps of the entries.
        if (change < 1e-16 || (sweep > 40 && change >= 0.5 * prev)) {
          last_change_ = std::max(last_change_, change);
          break;
        }
        prev = change;
      }
    }
    for (int y : comp) types_[static_cast<std::size_t>(y)].solved = true;
  };
  for (int t : pending_)
    if (!types_[static_cast<std::size_t>(t)].solved && !index.count(t)) visit(t);
  pending_.clear();
}

bool FaceGramCache::find(const Complex& c, const TriRings& r, std::uint32_t f, FaceGram& out) const {
  // The order to the signature's radius only: its labels are the first ones of the patch's
  // order (breadth first), and its signature is the one add_types takes from that order.
  std::uint32_t seeds[3], starts[3];
  face_seeds(c, f, seeds, starts);
  thread_local LocalOrder o;
  thread_local std::string sig;
  local_order_and_signature(c, r, seeds, starts, radii_.signature, o, sig);
  const auto it = index_.find(sig);
  if (it == index_.end()) return false;
  const Type& ty = types_[static_cast<std::size_t>(it->second)];
  if (!ty.solved) return false;
  out.verts.assign(o.vertex.begin(), o.vertex.begin() + ty.n);
  out.G = &ty.G;
  out.type = it->second;
  return true;
}

bool FaceGramCache::from_type(const Complex& c, const TriRings& r, std::uint32_t f, int type, FaceGram& out) const {
  const Type& ty = types_[static_cast<std::size_t>(type)];
  if (!ty.solved) return false;
  std::uint32_t seeds[3], starts[3];
  face_seeds(c, f, seeds, starts);
  thread_local LocalOrder o;
  local_order(r, seeds, starts, radii_.support, o);
  if (o.vertex.size() != static_cast<std::size_t>(ty.n))
    throw std::logic_error("tri_gram: face " + std::to_string(f) + " has " + std::to_string(o.vertex.size()) +
                           " functions, its type " + std::to_string(ty.n));
  out.verts.assign(o.vertex.begin(), o.vertex.end());
  out.G = &ty.G;
  out.type = type;
  return true;
}

FaceGramCache::FaceGram FaceGramCache::face_gram(const Complex& c, const TriRings& r, std::uint32_t f) {
  FaceGram g;
  if (find(c, r, f, g)) return g;
  const FaceRef at{&c, &r, f};
  add_types(std::span<const FaceRef>(&at, 1));
  if (!find(c, r, f, g)) throw std::logic_error("tri_gram: a face's new type was not made");
  return g;
}

}  // namespace sublift

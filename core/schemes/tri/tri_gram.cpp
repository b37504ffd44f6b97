#include "core/schemes/tri/tri_gram.h"

#include <cmath>
#include <functional>
#include <unordered_map>
#include <stdexcept>

#include "core/base/errors.h"
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

int FaceGramCache::type_of(const Complex& c, const TriRings& r, std::uint32_t f, LocalOrder* order_out) {
  std::uint32_t seeds[3], starts[3];
  face_seeds(c, f, seeds, starts);
  LocalOrder order = local_order(r, seeds, starts, radii_.patch);
  std::string sig = local_signature(c, r, order, radii_.signature);
  if (const auto it = index_.find(sig); it != index_.end()) {
    if (order_out) *order_out = std::move(order);
    return it->second;
  }
  const int id = static_cast<int>(types_.size());
  const std::string key = sig;  // to take the type back if its patch cannot be built
  index_.emplace(std::move(sig), id);
  types_.emplace_back();
  pending_.push_back(id);
  int n = 0;
  while (n < static_cast<int>(order.dist.size()) && order.dist[static_cast<std::size_t>(n)] <= radii_.support) ++n;
  types_[static_cast<std::size_t>(id)].n = n;

  // Subdivide a copy of the neighbourhood once; the face is the patch face on labels 0, 1, 2.
  const Complex patch = local_patch(c, order);
  std::uint32_t pf = UINT32_MAX;
  for (std::uint32_t g = 0; g < patch.num_faces() && pf == UINT32_MAX; ++g) {
    const auto row = patch.faces.row(g);
    if (row[0] < 3 && row[1] < 3 && row[2] < 3) pf = g;
  }
  if (pf == UINT32_MAX) throw std::logic_error("tri_gram: the face is missing from its own patch");
  Complex fine;
  TriStencils st;
  TriRings fine_rings;
  try {
    fine = refine_tri(patch);
    st = build_tri_stencils(patch, scheme_);
    fine_rings = build_tri_rings(fine);
  } catch (const TopologyError& e) {
    // local_patch always yields a manifold (it splits rim vertices where the surface meets
    // itself), so this is a defect; the builder is kept across calls: forget the half-made type.
    index_.erase(key);
    types_.pop_back();
    pending_.pop_back();
    throw std::logic_error("tri_gram: the patch around face " + std::to_string(f) + " cannot be subdivided: " + e.what());
  }
  const std::uint32_t nvp = patch.num_vertices;
  for (int k = 0; k < 4; ++k) {
    LocalOrder co;
    const int ct = type_of(fine, fine_rings, 4 * pf + static_cast<std::uint32_t>(k), &co);
    const int m = types_[static_cast<std::size_t>(ct)].n;
    std::vector<Eigen::Triplet<double>> terms;
    for (int i = 0; i < m; ++i) {
      const std::uint32_t v = co.vertex[static_cast<std::size_t>(i)];
      const auto add = [&](std::uint32_t a, double w) {
        if (a >= static_cast<std::uint32_t>(n))
          throw std::logic_error("tri_gram: N(f) does not close under subdivision (support radius too small)");
        terms.emplace_back(i, static_cast<int>(a), w);
      };
      for_each_stencil_weight(st, nvp, v, add);
    }
    Eigen::SparseMatrix<double> S(m, n);
    S.setFromTriplets(terms.begin(), terms.end());  // repeated (i, a) summed, as += did
    Type& t = types_[static_cast<std::size_t>(id)];
    t.child[static_cast<std::size_t>(k)] = ct;
    t.S[static_cast<std::size_t>(k)] = std::move(S);
  }
  if (order_out) *order_out = std::move(order);
  return id;
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
  // order (breadth first), and its signature is the one type_of takes from that order.
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
  return true;
}

FaceGramCache::FaceGram FaceGramCache::face_gram(const Complex& c, const TriRings& r, std::uint32_t f) {
  if (FaceGram g; find(c, r, f, g)) return g;
  LocalOrder o;
  const int t = type_of(c, r, f, &o);
  if (!pending_.empty()) solve_pending();
  FaceGram g;
  const Type& ty = types_[static_cast<std::size_t>(t)];
  g.verts.assign(o.vertex.begin(), o.vertex.begin() + ty.n);
  g.G = &ty.G;
  return g;
}

}  // namespace sublift

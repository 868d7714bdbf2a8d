// nanoknn.cpp — the anchor for the photon map's k-nearest search: nanoflann
// (Debian libnanoflann-dev, header-only C++) over the same float points, with
// a C interface so the C benchmark (bench/knn.c) can time both in one run.
//
// nanoflann 1.4 has L2 and L1 metrics but no L-infinity one. Its search keeps
// the lower bound to a cell as a sum of per-axis gaps (correct for L2 and L1),
// so a Chebyshev metric plugged into it prunes a cell when the sum of gaps
// exceeds the k-th distance although the max of the gaps may not: it can miss
// neighbours, i.e. it does less work than an exact cube search. That makes it
// a strict anchor for our exact L-infinity search; bench/knn.c counts the
// queries where its answer differs from ours.
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include <nanoflann.hpp>

namespace {

struct cloud {
	const float *xyz;   // n points, 3 floats each, at a stride of `stride` floats
	size_t n, stride;
	size_t kdtree_get_point_count() const { return n; }
	float kdtree_get_pt(size_t i, size_t d) const { return xyz[i * stride + d]; }
	template <class B> bool kdtree_get_bbox(B &) const { return false; }
};

// Chebyshev distance in nanoflann's metric shape (see above for its bound).
template <class T, class DS, class D = T, class I = uint32_t>
struct linf_adaptor {
	using ElementType = T;
	using DistanceType = D;
	const DS &ds;
	explicit linf_adaptor(const DS &d) : ds(d) {}
	D evalMetric(const T *a, const I b, size_t) const
	{
		D m = std::abs(a[0] - ds.kdtree_get_pt(b, 0));
		D y = std::abs(a[1] - ds.kdtree_get_pt(b, 1));
		D z = std::abs(a[2] - ds.kdtree_get_pt(b, 2));
		m = y > m ? y : m;
		return z > m ? z : m;
	}
	template <class U, class V> D accum_dist(const U a, const V b, size_t) const
	{
		return std::abs(a - b);
	}
};

struct metric_linf {
	template <class T, class DS, class I = uint32_t> struct traits {
		using distance_t = linf_adaptor<T, DS, T, I>;
	};
};

using tree_l2 = nanoflann::KDTreeSingleIndexAdaptor<
	nanoflann::L2_Simple_Adaptor<float, cloud, float, uint32_t>, cloud, 3, uint32_t>;
using tree_linf = nanoflann::KDTreeSingleIndexAdaptor<
	linf_adaptor<float, cloud, float, uint32_t>, cloud, 3, uint32_t>;

struct nano {
	cloud c;
	tree_l2 *l2;
	tree_linf *linf;
};

} // namespace

extern "C" {

// Builds both trees over n points (3 floats at every `stride` floats);
// leaf = nanoflann's leaf_max_size. NULL on failure.
void *
nano_build(const float *xyz, size_t n, size_t stride, int leaf)
{
	nano *t = new (std::nothrow) nano;
	if (!t)
		return nullptr;
	t->c = cloud{xyz, n, stride};
	try {
		nanoflann::KDTreeSingleIndexAdaptorParams p((size_t)leaf);
		/* the constructors build the trees */
		t->l2 = new tree_l2(3, t->c, p);
		t->linf = new tree_linf(3, t->c, p);
	} catch (...) {
		return nullptr;
	}
	return t;
}

// Builds the L2 tree alone and returns 0 (for timing the build).
int
nano_build_l2_only(const float *xyz, size_t n, size_t stride, int leaf)
{
	cloud c{xyz, n, stride};
	nanoflann::KDTreeSingleIndexAdaptorParams p((size_t)leaf);
	tree_l2 t(3, c, p);      // builds
	return t.size(t) == n ? 0 : -1;
}

// k nearest of x; linf selects the metric. Writes indices and distances
// (squared for L2), nearest first; returns how many were found.
int
nano_knn(void *vt, const float x[3], int k, int linf, uint32_t *idx, float *dist)
{
	nano *t = (nano *)vt;
	nanoflann::KNNResultSet<float, uint32_t, uint32_t> rs((uint32_t)k);
	rs.init(idx, dist);
	if (linf)
		t->linf->findNeighbors(rs, x, nanoflann::SearchParams());
	else
		t->l2->findNeighbors(rs, x, nanoflann::SearchParams());
	return (int)rs.size();
}

void
nano_free(void *vt)
{
	nano *t = (nano *)vt;
	if (!t)
		return;
	delete t->l2;
	delete t->linf;
	delete t;
}

}

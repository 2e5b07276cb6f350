#include "vulkan/gpu_bvh.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>

namespace lightsolver::detail {
namespace {

// Shallow leaves suit a GPU (one thread per ray, no SIMD over triangles); depth is capped below
// the shader's traversal stack (64 entries).
constexpr unsigned kMaxLeafSize = 4;
constexpr unsigned kMaxDepth = 48;

// Temporary build nodes, allocated in Embree's per-thread arenas and freed with the RTCBVH.
struct BuildNode {
  bool leaf;
};

struct InnerNode : BuildNode {
  RTCBounds bounds[2];
  const BuildNode* children[2];
};

struct LeafNode : BuildNode {
  unsigned count;
  unsigned geom[kMaxLeafSize], prim[kMaxLeafSize];
  RTCBounds bounds;  // only needed when the root is a leaf
};

void* create_node(RTCThreadLocalAllocator alloc, unsigned, void*) {
  return new (rtcThreadLocalAlloc(alloc, sizeof(InnerNode), 16)) InnerNode{{false}, {}, {}};
}

void set_children(void* node, void** children, unsigned count, void*) {
  for (unsigned i = 0; i < count && i < 2; ++i) {
    static_cast<InnerNode*>(node)->children[i] = static_cast<const BuildNode*>(children[i]);
  }
}

void set_bounds(void* node, const RTCBounds** bounds, unsigned count, void*) {
  for (unsigned i = 0; i < count && i < 2; ++i)
    static_cast<InnerNode*>(node)->bounds[i] = *bounds[i];
}

void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count,
                  void*) {
  auto* leaf = new (rtcThreadLocalAlloc(alloc, sizeof(LeafNode), 16)) LeafNode{};
  leaf->leaf = true;
  leaf->count = static_cast<unsigned>(count);
  leaf->bounds = {prims[0].lower_x, prims[0].lower_y, prims[0].lower_z, 0,
                  prims[0].upper_x, prims[0].upper_y, prims[0].upper_z, 0};
  for (size_t i = 0; i < count; ++i) {
    leaf->geom[i] = prims[i].geomID;
    leaf->prim[i] = prims[i].primID;
    RTCBounds& b = leaf->bounds;
    b.lower_x = std::min(b.lower_x, prims[i].lower_x);
    b.lower_y = std::min(b.lower_y, prims[i].lower_y);
    b.lower_z = std::min(b.lower_z, prims[i].lower_z);
    b.upper_x = std::max(b.upper_x, prims[i].upper_x);
    b.upper_y = std::max(b.upper_y, prims[i].upper_y);
    b.upper_z = std::max(b.upper_z, prims[i].upper_z);
  }
  return leaf;
}

glm::vec3 vertex(const PreparedMesh& m, std::uint32_t index) {
  const float* p = &m.vertices[3 * std::size_t(index)];
  return {p[0], p[1], p[2]};
}

// Triangles of the static meshes (mesh < 0) or of one movable mesh, in prepared coordinates.
std::vector<RTCBuildPrimitive> build_primitives(const PreparedScene& s, int only_mesh) {
  std::vector<RTCBuildPrimitive> prims;
  for (std::size_t g = 0; g < s.meshes.size(); ++g) {
    const PreparedMesh& m = s.meshes[g];
    if (only_mesh < 0 ? m.movable : int(g) != only_mesh) continue;
    for (std::size_t t = 0; 3 * t < m.indices.size(); ++t) {
      const glm::vec3 a = vertex(m, m.indices[3 * t]), b = vertex(m, m.indices[3 * t + 1]),
                      c = vertex(m, m.indices[3 * t + 2]);
      const glm::vec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
      prims.push_back(
          {lo.x, lo.y, lo.z, static_cast<unsigned>(g), hi.x, hi.y, hi.z, static_cast<unsigned>(t)});
    }
  }
  return prims;
}

// Depth-first flattening; children's boxes live in the parent.
class Flattener {
 public:
  Flattener(const PreparedScene& s, GpuGeometry& out) : s_(s), out_(out) {}

  void root(const BuildNode* root) {
    if (root == nullptr || root->leaf) {  // no triangles, or so few that the root is a leaf
      out_.nodes.push_back(empty_node());
      if (root) set_child(0, 0, root, static_cast<const LeafNode*>(root)->bounds);
      return;
    }
    add_inner(static_cast<const InnerNode*>(root));
  }

 private:
  static gpu::Node empty_node() {
    gpu::Node n{};
    n.child0 = n.child1 = gpu::kNone;
    return n;
  }

  std::uint32_t add_inner(const InnerNode* inner) {
    const auto index = static_cast<std::uint32_t>(out_.nodes.size());
    out_.nodes.push_back(empty_node());
    for (int c = 0; c < 2; ++c) {
      if (inner->children[c]) set_child(index, c, inner->children[c], inner->bounds[c]);
    }
    return index;
  }

  // Writes the child slot after recursing: out_.nodes may reallocate meanwhile.
  void set_child(std::uint32_t index, int slot, const BuildNode* child, const RTCBounds& b) {
    std::uint32_t target, count = 0;
    if (child->leaf) {
      const auto* leaf = static_cast<const LeafNode*>(child);
      target = static_cast<std::uint32_t>(out_.tris.size());
      count = leaf->count;
      for (unsigned i = 0; i < leaf->count; ++i) add_triangle(leaf->geom[i], leaf->prim[i]);
    } else {
      target = add_inner(static_cast<const InnerNode*>(child));
    }
    gpu::Node& n = out_.nodes[index];
    float* lo = slot == 0 ? n.lo0 : n.lo1;
    float* hi = slot == 0 ? n.hi0 : n.hi1;
    lo[0] = b.lower_x, lo[1] = b.lower_y, lo[2] = b.lower_z;
    hi[0] = b.upper_x, hi[1] = b.upper_y, hi[2] = b.upper_z;
    (slot == 0 ? n.child0 : n.child1) = target;
    (slot == 0 ? n.count0 : n.count1) = count;
  }

  void add_triangle(unsigned geom, unsigned prim) {
    const PreparedMesh& m = s_.meshes[geom];
    gpu::Tri t{};
    const glm::vec3 v[3] = {vertex(m, m.indices[3 * prim]), vertex(m, m.indices[3 * prim + 1]),
                            vertex(m, m.indices[3 * prim + 2])};
    float* dst[3] = {t.v0, t.v1, t.v2};
    for (int k = 0; k < 3; ++k) dst[k][0] = v[k].x, dst[k][1] = v[k].y, dst[k][2] = v[k].z;
    t.mesh = geom;
    t.prim = prim;
    out_.tris.push_back(t);
    out_.normals.emplace_back(m.normals[prim], 0.0f);
  }

  const PreparedScene& s_;
  GpuGeometry& out_;
};

struct DeviceDeleter {
  void operator()(RTCDeviceTy* d) const { rtcReleaseDevice(d); }
};
struct BvhDeleter {
  void operator()(RTCBVHTy* b) const { rtcReleaseBVH(b); }
};

// Builds one BVH over `prims` and appends it to `out`; returns its root node.
std::uint32_t append_bvh(RTCDevice device, const PreparedScene& scene,
                         std::vector<RTCBuildPrimitive>& prims, GpuGeometry& out) {
  const auto root_index = static_cast<std::uint32_t>(out.nodes.size());
  if (prims.empty()) {
    Flattener(scene, out).root(nullptr);
    return root_index;
  }
  std::unique_ptr<RTCBVHTy, BvhDeleter> bvh(rtcNewBVH(device));
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;  // binned SAH without spatial splits
  args.maxBranchingFactor = 2;
  args.maxDepth = kMaxDepth;
  args.maxLeafSize = kMaxLeafSize;
  args.bvh = bvh.get();
  args.primitives = prims.data();
  args.primitiveCount = prims.size();
  args.primitiveArrayCapacity = prims.size();
  args.createNode = create_node;
  args.setNodeChildren = set_children;
  args.setNodeBounds = set_bounds;
  args.createLeaf = create_leaf;
  const void* root = rtcBuildBVH(&args);
  if (!root) {
    throw std::runtime_error("Embree: rtcBuildBVH failed (error " +
                             std::to_string(int(rtcGetDeviceError(device))) + ")");
  }
  Flattener(scene, out).root(static_cast<const BuildNode*>(root));
  return root_index;
}

// Box of a mesh in its prepared coordinates.
void mesh_bounds(const PreparedMesh& m, glm::vec3& lo, glm::vec3& hi) {
  lo = glm::vec3(std::numeric_limits<float>::max());
  hi = -lo;
  for (std::uint32_t i : m.indices) {
    lo = glm::min(lo, vertex(m, i));
    hi = glm::max(hi, vertex(m, i));
  }
}

}  // namespace

GpuGeometry build_gpu_geometry(const PreparedScene& scene) {
  GpuGeometry out;
  out.tris.reserve(scene.triangle_count);
  out.normals.reserve(scene.triangle_count);
  std::unique_ptr<RTCDeviceTy, DeviceDeleter> device(rtcNewDevice(nullptr));
  if (!device) throw std::runtime_error("Embree: cannot create a device for the GPU BVH");
  std::vector<RTCBuildPrimitive> prims = build_primitives(scene, -1);
  append_bvh(device.get(), scene, prims, out);  // static geometry: root 0
  for (std::size_t g = 0; g < scene.meshes.size(); ++g) {
    if (!scene.meshes[g].movable) continue;
    prims = build_primitives(scene, int(g));
    GpuInstanceRoot inst{static_cast<std::uint32_t>(g), 0, {}, {}};
    inst.root = append_bvh(device.get(), scene, prims, out);
    mesh_bounds(scene.meshes[g], inst.lo, inst.hi);
    out.instances.push_back(inst);
  }
  return out;
}

}  // namespace lightsolver::detail

// The host/GPU contract of trace.comp: the storage buffers and specialisation constants the
// backend creates (gpu::kBuffers, gpu::kSpecConstants, numbered by Shaders/trace_bindings.h)
// against what the compiled shader declares, read back from its SPIR-V by a small word walker.
// Block and constant names come from a build without -O (which strips OpName); the numbers are
// checked on the optimised SPIR-V the backend loads too. No device needed.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdint>
#include <map>
#include <set>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "types/luminaire_types.hpp"
#include "model/prepared_scene.hpp"
#include "lightsolver/scene.hpp"
#include "native/core/scene_builders.hpp"
#include "vulkan/gpu_layout.hpp"
#include "vulkan/gpu_scene.hpp"
#include "vulkan/shaders.hpp"

namespace lightsolver::test {
namespace {

constexpr std::uint32_t kTraceNamedSpirv[] = {
#include "trace.named.spv.inc"
};

// The resource interface of a SPIR-V module.
struct Interface {
  std::map<std::uint32_t, std::string> buffers;  // binding (set 0) -> GLSL block name
  std::map<std::uint32_t, std::string> specs;    // SpecId -> constant name
  std::vector<std::string> errors;               // a set other than 0, a number used twice
};

// Opcodes, decorations and enumerants from the SPIR-V specification (sections 3.x).
constexpr std::uint32_t kMagic = 0x07230203u;
constexpr std::uint32_t kOpName = 5, kOpTypePointer = 32, kOpSpecConstantComposite = 51,
                        kOpVariable = 59, kOpDecorate = 71;
constexpr std::uint32_t kSpecIdDecoration = 1, kBuiltInDecoration = 11, kBindingDecoration = 33,
                        kDescriptorSetDecoration = 34;
constexpr std::uint32_t kWorkgroupSizeBuiltIn = 25;

// A literal string: UTF-8 bytes packed little-endian into words, NUL-terminated.
std::string literal(std::span<const std::uint32_t> words) {
  std::string out;
  for (const std::uint32_t w : words) {
    for (int byte = 0; byte < 4; ++byte) {
      const char c = static_cast<char>((w >> (8 * byte)) & 0xFFu);
      if (c == '\0') return out;
      out += c;
    }
  }
  return out;
}

struct Module {
  using Decorations = std::map<std::uint32_t, std::uint32_t>;      // decoration -> its operand
  std::map<std::uint32_t, std::string> names;                      // OpName
  std::map<std::uint32_t, Decorations> decorations;                // per id
  std::map<std::uint32_t, std::uint32_t> pointee;                  // pointer type -> type
  std::map<std::uint32_t, std::uint32_t> variables;                // variable -> its type
  std::map<std::uint32_t, std::vector<std::uint32_t>> composites;  // spec composites

  std::string name(std::uint32_t id) const {
    const auto it = names.find(id);
    return it == names.end() ? std::string() : it->second;
  }
  const std::uint32_t* decoration(std::uint32_t id, std::uint32_t dec) const {
    const auto it = decorations.find(id);
    if (it == decorations.end()) return nullptr;
    const auto d = it->second.find(dec);
    return d == it->second.end() ? nullptr : &d->second;
  }
};

Module parse(std::span<const std::uint32_t> words) {
  if (words.size() < 5 || words[0] != kMagic) throw std::runtime_error("not a SPIR-V module");
  Module m;
  for (std::size_t i = 5; i < words.size();) {
    const std::uint32_t count = words[i] >> 16, op = words[i] & 0xFFFFu;
    if (count == 0 || i + count > words.size()) throw std::runtime_error("truncated SPIR-V");
    const std::span<const std::uint32_t> w = words.subspan(i, count);
    if (op == kOpName && count >= 3) m.names[w[1]] = literal(w.subspan(2));
    // Binding, DescriptorSet, SpecId and BuiltIn carry one operand.
    if (op == kOpDecorate && count >= 4) m.decorations[w[1]][w[2]] = w[3];
    if (op == kOpTypePointer && count == 4) m.pointee[w[1]] = w[3];
    if (op == kOpVariable && count >= 4) m.variables[w[2]] = w[1];
    if (op == kOpSpecConstantComposite) m.composites[w[2]].assign(w.begin() + 3, w.end());
    i += count;
  }
  return m;
}

// glslang names the block's struct type (the variable of an anonymous block is named "").
void add_buffers(const Module& m, Interface& out) {
  for (const auto& [variable, type] : m.variables) {
    const std::uint32_t* binding = m.decoration(variable, kBindingDecoration);
    if (!binding) continue;
    const std::uint32_t* set = m.decoration(variable, kDescriptorSetDecoration);
    const auto pointee = m.pointee.find(type);
    const std::string block = pointee == m.pointee.end() ? "" : m.name(pointee->second);
    if (!set || *set != 0) out.errors.push_back("block " + block + " is not in set 0");
    if (!out.buffers.emplace(*binding, block).second) {
      out.errors.push_back("binding " + std::to_string(*binding) + " holds both " +
                           out.buffers[*binding] + " and " + block);
    }
  }
}

// local_size_x_id makes an unnamed constant: the x of the WorkgroupSize built-in composite.
void add_specs(const Module& m, Interface& out) {
  std::set<std::uint32_t> workgroup_x;
  for (const auto& [id, parts] : m.composites) {
    const std::uint32_t* builtin = m.decoration(id, kBuiltInDecoration);
    if (builtin && *builtin == kWorkgroupSizeBuiltIn && !parts.empty())
      workgroup_x.insert(parts[0]);
  }
  for (const auto& [id, decorations] : m.decorations) {
    const auto spec = decorations.find(kSpecIdDecoration);
    if (spec == decorations.end()) continue;
    const std::string name = workgroup_x.count(id) ? "local_size_x" : m.name(id);
    if (!out.specs.emplace(spec->second, name).second) {
      out.errors.push_back("constant_id " + std::to_string(spec->second) + " is used twice");
    }
  }
}

Interface reflect(std::span<const std::uint32_t> spirv) {
  const Module m = parse(spirv);
  Interface out;
  add_buffers(m, out);
  add_specs(m, out);
  return out;
}

using Table = std::map<std::uint32_t, std::string>;

Table host_buffers() {
  Table out;
  for (const auto& row : detail::gpu::kBuffers) out[row.binding] = row.block;
  return out;
}

Table host_specs() {
  Table out;
  for (const auto& row : detail::gpu::kSpecConstants) out[row.id] = row.name;
  return out;
}

// Every host row is declared by the shader at its number, under its name where the shader
// still has names.
void expect_declared(const Table& shader, const Table& host, const std::string& what, bool named) {
  for (const auto& [number, name] : host) {
    const auto it = shader.find(number);
    if (it == shader.end()) {
      ADD_FAILURE() << "the host sets " << name << " at " << what << " " << number
                    << " but trace.comp has nothing there";
    } else if (named) {
      EXPECT_EQ(it->second, name) << what << " " << number << ": shader vs host table";
    }
  }
}

// Everything the shader declares is in the host table.
void expect_known(const Table& shader, const Table& host, const std::string& what) {
  for (const auto& [number, name] : shader) {
    EXPECT_TRUE(host.count(number)) << "trace.comp declares " << name << " at " << what << " "
                                    << number << ", which the host table does not have";
  }
}

TEST(Bindings, ReflectionReadsTheShader) {
  // Guards the walker itself: a reflection that found nothing would make the tests below vacuous.
  const Interface named = reflect(kTraceNamedSpirv);
  EXPECT_EQ(named.buffers.size(), detail::gpu::kBindingCount);
  EXPECT_EQ(named.buffers.at(0), "Nodes");
  EXPECT_EQ(named.specs.at(1), "HAS_DIFFUSE");
  EXPECT_THROW(reflect(std::span(kTraceNamedSpirv).subspan(1)), std::runtime_error);
}

TEST(Bindings, BlocksMatchTheHostTable) {
  const Interface shader = reflect(kTraceNamedSpirv);
  EXPECT_TRUE(shader.errors.empty()) << ::testing::PrintToString(shader.errors);
  expect_declared(shader.buffers, host_buffers(), "binding", true);
  expect_known(shader.buffers, host_buffers(), "binding");
}

TEST(Bindings, SpecConstantsMatchTheHostTable) {
  const Interface shader = reflect(kTraceNamedSpirv);
  EXPECT_TRUE(shader.errors.empty()) << ::testing::PrintToString(shader.errors);
  expect_declared(shader.specs, host_specs(), "constant_id", true);
  expect_known(shader.specs, host_specs(), "constant_id");
}

// The SPIR-V the backend loads (optimised, without names): the optimiser kept every binding, so
// every buffer the backend creates is one the shader reads at that binding. Constants that the
// optimised code never reads would be dropped; every luminaire type's switch must be read (its
// emit.glsl branch sits behind it), so a type whose branch is missing fails here.
TEST(Bindings, EmbeddedShaderHasEveryBinding) {
  const Interface shader = reflect(detail::shaders::trace());
  EXPECT_TRUE(shader.errors.empty()) << ::testing::PrintToString(shader.errors);
  expect_declared(shader.buffers, host_buffers(), "binding", false);
  expect_known(shader.buffers, host_buffers(), "binding");
  expect_known(shader.specs, host_specs(), "constant_id");
  EXPECT_TRUE(shader.specs.count(detail::gpu::kWorkgroupSize));
  for (const auto& type : detail::luminaire_types()) {
    EXPECT_TRUE(shader.specs.count(detail::gpu_luminaire_type(type.type).feature)) << type.name;
  }
}

// Every luminaire type of core's table has a GPU row (generated from LS_LUMINAIRE_TYPES,
// Shaders/shared/luminaires.h), with its own code and its own switch, and the code is the enum
// value the CPU side uses; the GPU has no row core does not have.
TEST(GpuLuminaireTypes, OneRowPerCoreType) {
  std::set<std::uint32_t> codes, features;
  for (const auto& type : detail::luminaire_types()) {
    const auto& row = detail::gpu_luminaire_type(type.type);
    EXPECT_EQ(row.type, type.type) << type.name;
    EXPECT_EQ(row.code, static_cast<std::uint32_t>(type.type)) << type.name;
    EXPECT_TRUE(codes.insert(row.code).second) << type.name;
    EXPECT_TRUE(features.insert(row.feature).second) << type.name;
    EXPECT_EQ(row.feature, detail::gpu::luminaire_switch(row.code)) << type.name;
    EXPECT_TRUE(host_specs().count(row.feature)) << type.name;
  }
  EXPECT_EQ(detail::gpu::kGpuLuminaireTypeCount, detail::luminaire_types().size());
}

// The switch names the list gives are the shader's: the non-optimised SPIR-V declares HAS_<TYPE>
// at each type's id, for the type the scene file names <type>.
TEST(GpuLuminaireTypes, SwitchesAreNamedAfterTheirTypes) {
  const Interface shader = reflect(kTraceNamedSpirv);
  for (const auto& type : detail::luminaire_types()) {
    std::string expected = "HAS_";
    for (const char* c = type.name; *c; ++c) expected += static_cast<char>(std::toupper(*c));
    const auto it = shader.specs.find(detail::gpu_luminaire_type(type.type).feature);
    ASSERT_NE(it, shader.specs.end()) << type.name;
    EXPECT_EQ(it->second, expected) << type.name;
  }
}

// pack_scene sets every feature switch once (the backend adds the workgroup size).
TEST(Bindings, FeaturesSetEverySwitchOnce) {
  const detail::PreparedScene prepared = detail::prepare(room_with_block(dvec3(0.0)));
  std::multiset<std::uint32_t> ids;
  for (const vkw::SpecConstant& c : detail::pack_scene(prepared).features) ids.insert(c.id);
  std::multiset<std::uint32_t> expected;
  for (const auto& row : detail::gpu::kSpecConstants) {
    // The backend sets these two: the workgroup size and the run's sampler (set_quasi_random).
    if (row.id != detail::gpu::kWorkgroupSize && row.id != detail::gpu::kQuasiRandom) {
      expected.insert(row.id);
    }
  }
  EXPECT_EQ(ids, expected);
}

// The switches are core's scene analysis: a mirror that absorbs everything needs no mirror
// code (scatter.glsl absorbs it), one luminaire no CDF search, no observer or movable mesh.
TEST(Bindings, FeaturesAreTheSceneAnalysis) {
  Scene s = room_with_block(dvec3(0.0));
  add_material(s, "black mirror", Material::Type::Mirror, 0.0);
  s.meshes[1].material = static_cast<int>(s.materials.size() - 1);
  validate(s);
  const detail::PreparedScene prepared = detail::prepare(s);
  std::map<std::uint32_t, std::uint32_t> on;
  for (const vkw::SpecConstant& c : detail::pack_scene(prepared).features) on[c.id] = c.value;
  namespace g = detail::gpu;
  EXPECT_EQ(on[g::kHasDiffuse], 1u);
  EXPECT_EQ(on[g::kHasMirror], 0u);
  EXPECT_EQ(on[g::kHasGlass], 0u);
  EXPECT_EQ(on[g::kHasGlossy], 0u);
  EXPECT_EQ(on[g::kHasGrids], 1u);
  EXPECT_EQ(on[g::kHasSurfaceBins], 1u);
  EXPECT_EQ(on[g::kManyLuminaires], 0u);
  EXPECT_EQ(on[g::kHasInstances], 0u);
  EXPECT_EQ(on[detail::gpu_luminaire_type(Luminaire::Type::Spot).feature], 1u);
  EXPECT_EQ(on[detail::gpu_luminaire_type(Luminaire::Type::Point).feature], 0u);
}

}  // namespace
}  // namespace lightsolver::test

// Meshes and their primitives: attribute names, accessor formats and layouts, morph targets,
// and what the primitive's material asks of it.
#include "core/gltf/validate/validate_semantics_read.h"

#include <map>
#include <set>

namespace irad::gltf::sem {

using nlohmann::json;

namespace {

// An attribute semantic split into its name and set index ("TEXCOORD_1" → TEXCOORD, 1).
struct Semantic {
  std::string name; // POSITION, NORMAL, TANGENT, TEXCOORD, COLOR, JOINTS, WEIGHTS, or "_"
  int set = -1;     // for the indexed semantics
};

std::optional<Semantic> parse_semantic(const std::string& s) {
  if (s == "POSITION" || s == "NORMAL" || s == "TANGENT") return Semantic{s, -1};
  if (!s.empty() && s[0] == '_') return Semantic{"_", -1};
  for (const char* base : {"TEXCOORD", "COLOR", "JOINTS", "WEIGHTS"}) {
    const std::string prefix = std::string(base) + "_";
    if (s.rfind(prefix, 0) != 0) continue;
    const std::string digits = s.substr(prefix.size());
    if (digits.empty() || digits.size() > 6 || (digits[0] == '0' && digits.size() > 1))
      return std::nullopt;
    for (char c : digits)
      if (c < '0' || c > '9') return std::nullopt;
    return Semantic{base, std::stoi(digits)};
  }
  return std::nullopt;
}

struct Format {
  const char* type;
  std::int64_t component;
  int normalized; // 0 no, 1 yes, 2 either
};

bool matches(const AccessorView& a, std::initializer_list<Format> formats) {
  for (const Format& f : formats)
    if (a.type == f.type && a.component_type == f.component &&
        (f.normalized == 2 || (f.normalized == 1) == a.normalized))
      return true;
  return false;
}

// Whether the accessor's format is allowed for the semantic (KHR_mesh_quantization widens it).
bool format_ok(const Semantic& s, const AccessorView& a, bool quantized, bool target) {
  if (s.name == "POSITION" || (target && (s.name == "NORMAL" || s.name == "TANGENT"))) {
    if (matches(a, {{"VEC3", kFloat, 0}})) return true;
    if (!quantized) return false;
    if (target) return matches(a, {{"VEC3", kByte, 2}, {"VEC3", kShort, 2}});
    return matches(a, {{"VEC3", kByte, 2},
                       {"VEC3", kUnsignedByte, 2},
                       {"VEC3", kShort, 2},
                       {"VEC3", kUnsignedShort, 2}});
  }
  if (target) return true; // other morphed semantics: not checked
  if (s.name == "NORMAL")
    return matches(a, {{"VEC3", kFloat, 0}}) ||
           (quantized && matches(a, {{"VEC3", kByte, 1}, {"VEC3", kShort, 1}}));
  if (s.name == "TANGENT")
    return matches(a, {{"VEC4", kFloat, 0}}) ||
           (quantized && matches(a, {{"VEC4", kByte, 1}, {"VEC4", kShort, 1}}));
  if (s.name == "TEXCOORD")
    return matches(
               a, {{"VEC2", kFloat, 0}, {"VEC2", kUnsignedByte, 1}, {"VEC2", kUnsignedShort, 1}}) ||
           (quantized && matches(a, {{"VEC2", kByte, 2},
                                     {"VEC2", kShort, 2},
                                     {"VEC2", kUnsignedByte, 0},
                                     {"VEC2", kUnsignedShort, 0}}));
  if (s.name == "COLOR")
    return matches(a, {{"VEC3", kFloat, 0},
                       {"VEC3", kUnsignedByte, 1},
                       {"VEC3", kUnsignedShort, 1},
                       {"VEC4", kFloat, 0},
                       {"VEC4", kUnsignedByte, 1},
                       {"VEC4", kUnsignedShort, 1}});
  if (s.name == "JOINTS")
    return matches(a, {{"VEC4", kUnsignedByte, 0}, {"VEC4", kUnsignedShort, 0}});
  if (s.name == "WEIGHTS")
    return matches(a,
                   {{"VEC4", kFloat, 0}, {"VEC4", kUnsignedByte, 1}, {"VEC4", kUnsignedShort, 1}});
  return true; // custom attributes
}

struct MeshState {
  bool quantized = false;
  // bufferView → the accessors read from it as vertex attributes (of uncompressed primitives).
  std::map<std::int64_t, std::set<std::int64_t>> vertex_views;
};

// Fills st.vertex_views from every attribute and morph target of every uncompressed primitive.
void collect_vertex_views(const Context& ctx, MeshState& st) {
  auto add = [&](const json& acc) {
    const auto ai = as_int(&acc);
    const json* a = ai ? ctx.object("accessors", *ai) : nullptr;
    const auto view = a != nullptr ? index(*a, "bufferView") : std::nullopt;
    if (view) st.vertex_views[*view].insert(*ai);
  };
  for (const json& mesh : ctx.list("meshes")) {
    const json* prims = member(mesh, "primitives");
    if (prims == nullptr || !prims->is_array()) continue;
    for (const json& prim : *prims) {
      const json* ext = member(prim, "extensions");
      if (ext != nullptr && has(*ext, "KHR_draco_mesh_compression")) continue;
      if (const json* attrs = member(prim, "attributes"); attrs != nullptr && attrs->is_object())
        for (const json& acc : *attrs) add(acc);
      const json* targets = member(prim, "targets");
      if (targets == nullptr || !targets->is_array()) continue;
      for (const json& t : *targets)
        if (t.is_object())
          for (const json& acc : t) add(acc);
    }
  }
}

// Checks common to base and morph-target attributes.
void check_attribute_accessor(const Context& ctx, MeshState& st, const Semantic& s,
                              std::int64_t acc, bool target, const std::string& ptr) {
  const auto a = accessor_view(ctx, acc);
  if (!a || !a->valid) return;
  if (s.name == "_" && a->component_type == kUnsignedInt)
    ctx.add(ptr, "MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_UNSIGNED_INT",
            "a vertex attribute cannot use UNSIGNED_INT components");
  else if (!format_ok(s, *a, st.quantized, target))
    ctx.add(ptr, "MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT",
            "accessor format " + a->type + "/" + std::to_string(a->component_type) +
                " is not allowed for this attribute");
  if (s.name == "POSITION" &&
      (!has(*ctx.object("accessors", acc), "min") || !has(*ctx.object("accessors", acc), "max")))
    ctx.add(ptr, "MESH_PRIMITIVE_POSITION_ACCESSOR_WITHOUT_BOUNDS",
            "a POSITION accessor must declare min and max");
  const json* bv = a->buffer_view ? ctx.object("bufferViews", *a->buffer_view) : nullptr;
  if (bv == nullptr) return;
  const std::int64_t view_offset = index(*bv, "byteOffset").value_or(0);
  if (!sane(view_offset)) return;
  if ((view_offset + a->byte_offset) % 4 != 0 || (a->byte_stride && *a->byte_stride % 4 != 0))
    ctx.add(ptr, "MESH_PRIMITIVE_ACCESSOR_UNALIGNED",
            "vertex attribute data must be aligned to 4 bytes");
  // The JSON's objects are sorted by key, so "first" is the accessor with the lowest index.
  const auto users = st.vertex_views.find(*a->buffer_view);
  if (!a->byte_stride && users != st.vertex_views.end() && users->second.size() > 1 &&
      *users->second.begin() != acc)
    ctx.add(ptr, "MESH_PRIMITIVE_ACCESSOR_WITHOUT_BYTESTRIDE",
            "several vertex accessors share this buffer view, which has no byteStride");
}

std::int64_t count_of(const Context& ctx, std::int64_t acc) {
  const auto a = accessor_view(ctx, acc);
  return a && a->valid ? a->count : -1;
}

void check_indices(const Context& ctx, std::int64_t acc, const std::string& ptr) {
  const auto a = accessor_view(ctx, acc);
  if (!a || !a->valid) return;
  if (a->type != "SCALAR" ||
      (a->component_type != kUnsignedByte && a->component_type != kUnsignedShort &&
       a->component_type != kUnsignedInt))
    ctx.add(ptr, "MESH_PRIMITIVE_INDICES_ACCESSOR_INVALID_FORMAT",
            "indices must be SCALAR unsigned byte, short or int");
  if (a->byte_stride)
    ctx.add(ptr, "MESH_PRIMITIVE_INDICES_ACCESSOR_WITH_BYTESTRIDE",
            "the indices' buffer view cannot have a byteStride");
}

// The parts of a material that ask for something of the primitive: "" for the material's core
// members, else the extensions whose objects ask. An issue raised by extensions only carries
// their names (Issue::extensions); one the core members raise carries none.
std::vector<std::string> raised_by(const std::set<std::string>& parts) {
  if (parts.empty() || parts.count("") != 0) return {};
  return {parts.begin(), parts.end()};
}

// TEXCOORD_n sets, NORMAL/TANGENT presence: what a material needs from the primitive.
void check_material(const Context& ctx, const json& prim, const std::set<std::string>& names,
                    int texcoords, const std::string& ptr) {
  const auto mi = index(prim, "material");
  const json* mat = mi ? ctx.object("materials", *mi) : nullptr;
  if (mat == nullptr) return;
  std::set<std::string> too_few; // the parts reading a set the primitive lacks
  // Every texture binding (an object member named *Texture), down to a bounded depth. `part` is
  // "" in the core material; each member of the material's "extensions" object is its own part.
  auto walk = [&](auto& self, const json& obj, int depth, const std::string& part,
                  bool extension_list) -> void {
    if (!obj.is_object() || depth > 8) return;
    for (const auto& [key, v] : obj.items()) {
      const std::string& owner = extension_list ? key : part;
      if (key.size() > 7 && key.compare(key.size() - 7, 7, "Texture") == 0 && v.is_object() &&
          has(v, "index")) {
        std::int64_t set = index(v, "texCoord").value_or(0);
        const json* ext = member(v, "extensions");
        const json* tt = ext != nullptr ? member(*ext, "KHR_texture_transform") : nullptr;
        if (tt != nullptr) set = index(*tt, "texCoord").value_or(set);
        if (set >= texcoords) too_few.insert(owner);
      }
      self(self, v, depth + 1, owner, depth == 0 && key == "extensions");
    }
  };
  walk(walk, *mat, 0, "", false);
  if (!too_few.empty())
    ctx.add(at(ptr, "material"), "MESH_PRIMITIVE_TOO_FEW_TEXCOORDS",
            "the material reads a texture coordinate set the primitive does not have",
            raised_by(too_few));
  const json* ext = member(*mat, "extensions");
  const json* clearcoat = ext != nullptr ? member(*ext, "KHR_materials_clearcoat") : nullptr;
  std::set<std::string> needs_tangents; // the extensions whose normals need a tangent frame
  if (ext != nullptr && has(*ext, "KHR_materials_anisotropy"))
    needs_tangents.insert("KHR_materials_anisotropy");
  if (clearcoat != nullptr && has(*clearcoat, "clearcoatNormalTexture"))
    needs_tangents.insert("KHR_materials_clearcoat");
  if (!needs_tangents.empty() && names.count("TANGENT") == 0 && !has(*mat, "normalTexture"))
    ctx.add(at(ptr, "material"), "MESH_PRIMITIVE_NO_TANGENT_SPACE",
            "the material needs tangents and neither the primitive nor a normal map gives them",
            raised_by(needs_tangents));
}

void check_attributes(const Context& ctx, MeshState& st, const json& prim, const std::string& ptr) {
  const json* attrs = member(prim, "attributes");
  if (attrs == nullptr || !attrs->is_object()) return;
  const std::string ap = at(ptr, "attributes");
  std::map<std::string, std::set<int>> sets;
  std::set<std::string> names;
  // The reference count is POSITION's (else the first attribute's in key order).
  std::int64_t first_count = -1;
  if (const json* pos = member(*attrs, "POSITION");
      pos != nullptr && as_int(pos) && ctx.object("accessors", *as_int(pos)))
    first_count = count_of(ctx, *as_int(pos));
  for (const auto& [name, acc] : attrs->items()) {
    const std::string p = at(ap, name);
    const auto s = parse_semantic(name);
    if (!s) {
      ctx.add(p, "MESH_PRIMITIVE_INVALID_ATTRIBUTE", "'" + name + "' is not an attribute name");
      continue;
    }
    names.insert(name);
    if (s->set >= 0) sets[s->name].insert(s->set);
    const auto ai = as_int(&acc);
    if (!ai || ctx.object("accessors", *ai) == nullptr) continue;
    check_attribute_accessor(ctx, st, *s, *ai, false, p);
    const std::int64_t n = count_of(ctx, *ai);
    if (first_count < 0)
      first_count = n;
    else if (n >= 0 && n != first_count)
      ctx.add(p, "MESH_PRIMITIVE_UNEQUAL_ACCESSOR_COUNT",
              "the primitive's attribute accessors have different counts");
  }
  for (const auto& [semantic, used] : sets)
    if (*used.rbegin() + 1 != static_cast<int>(used.size()))
      ctx.add(ap, "MESH_PRIMITIVE_INDEXED_SEMANTIC_CONTINUITY",
              "the " + semantic + "_n sets must be numbered from 0 without gaps");
  if (sets["JOINTS"].size() != sets["WEIGHTS"].size())
    ctx.add(ap, "MESH_PRIMITIVE_JOINTS_WEIGHTS_MISMATCH",
            "the numbers of JOINTS_n and WEIGHTS_n attributes differ");
  check_material(ctx, prim, names, static_cast<int>(sets["TEXCOORD"].size()), ptr);
}

void check_targets(const Context& ctx, MeshState& st, const json& prim, const std::string& ptr) {
  const json* targets = member(prim, "targets");
  const json* attrs = member(prim, "attributes");
  if (targets == nullptr || !targets->is_array() || attrs == nullptr || !attrs->is_object()) return;
  for (std::size_t t = 0; t < targets->size(); ++t) {
    const json& target = (*targets)[t];
    if (!target.is_object()) continue;
    const std::string tp = at(at(ptr, "targets"), static_cast<std::int64_t>(t));
    for (const auto& [name, acc] : target.items()) {
      const std::string p = at(tp, name);
      const auto s = parse_semantic(name);
      if (!s)
        ctx.add(p, "MESH_PRIMITIVE_INVALID_ATTRIBUTE", "'" + name + "' is not an attribute name");
      const json* base = member(*attrs, name);
      if (base == nullptr) {
        ctx.add(p, "MESH_PRIMITIVE_MORPH_TARGET_NO_BASE_ACCESSOR",
                "the primitive has no '" + name + "' attribute to morph");
        continue;
      }
      const auto ai = as_int(&acc);
      if (!s || !ai || ctx.object("accessors", *ai) == nullptr) continue;
      check_attribute_accessor(ctx, st, *s, *ai, true, p);
      const auto bi = as_int(base);
      const std::int64_t bc = bi ? count_of(ctx, *bi) : -1;
      const std::int64_t tc = count_of(ctx, *ai);
      if (bc >= 0 && tc >= 0 && bc != tc)
        ctx.add(p, "MESH_PRIMITIVE_MORPH_TARGET_INVALID_ATTRIBUTE_COUNT",
                "the morph target's accessor count differs from the base attribute's");
    }
  }
}

void check_mesh(const Context& ctx, MeshState& st, const json& mesh, std::int64_t m) {
  const json* prims = member(mesh, "primitives");
  if (prims == nullptr || !prims->is_array()) return;
  const std::string mp = at("/meshes", m);
  std::optional<std::size_t> targets0;
  for (std::size_t p = 0; p < prims->size(); ++p) {
    const json& prim = (*prims)[p];
    if (!prim.is_object()) continue;
    const std::string pp = at(at(mp, "primitives"), static_cast<std::int64_t>(p));
    const json* ext = member(prim, "extensions");
    const bool draco = ext != nullptr && has(*ext, "KHR_draco_mesh_compression");
    MeshState draco_state{st.quantized, {}}; // Draco accessors have no views to share
    check_attributes(ctx, draco ? draco_state : st, prim, pp);
    if (const auto ind = index(prim, "indices"); ind && ctx.object("accessors", *ind))
      check_indices(ctx, *ind, at(pp, "indices"));
    check_targets(ctx, draco ? draco_state : st, prim, pp);
    // Only primitives with attributes take part (the schema half reports the others).
    const json* attrs = member(prim, "attributes");
    if (attrs == nullptr || !attrs->is_object() || attrs->empty()) continue;
    const std::size_t n = array_size(prim, "targets");
    if (!targets0)
      targets0 = n;
    else if (n != *targets0)
      ctx.add(has(prim, "targets") ? at(pp, "targets") : pp,
              "MESH_PRIMITIVES_UNEQUAL_TARGETS_COUNT",
              "the mesh's primitives have different numbers of morph targets");
  }
  const json* weights = member(mesh, "weights");
  if (weights != nullptr && weights->is_array() && targets0 && weights->size() != *targets0)
    ctx.add(at(mp, "weights"), "MESH_INVALID_WEIGHTS_COUNT",
            "the mesh's weights do not match its number of morph targets");
}

} // namespace

void check_meshes(const Context& ctx) {
  MeshState st;
  st.quantized = extension_used(ctx.root, "KHR_mesh_quantization");
  collect_vertex_views(ctx, st);
  const json& meshes = ctx.list("meshes");
  for (std::size_t m = 0; m < meshes.size(); ++m)
    if (meshes[m].is_object()) check_mesh(ctx, st, meshes[m], static_cast<std::int64_t>(m));
}

} // namespace irad::gltf::sem

// OpenMesh readers and writers driven through our own importer and exporter, so that faces reach us
// in file order without OpenMesh's halfedge structure (which reorders or drops non-manifold faces).
#include "mesh/openmesh_bridge.h"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/exporter/BaseExporter.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <string>

namespace rtlab::detail {

namespace {

namespace om = OpenMesh;
namespace omio = OpenMesh::IO;

/// Silences OpenMesh's log streams for one call and restores their state afterwards.
class QuietOpenMesh {
public:
    QuietOpenMesh()
        : err_(::omerr().is_enabled()), log_(::omlog().is_enabled()), out_(::omout().is_enabled()) {
        ::omerr().disable();
        ::omlog().disable();
        ::omout().disable();
    }
    ~QuietOpenMesh() {
        restore(::omerr(), err_);
        restore(::omlog(), log_);
        restore(::omout(), out_);
    }
    QuietOpenMesh(const QuietOpenMesh&) = delete;
    QuietOpenMesh& operator=(const QuietOpenMesh&) = delete;

private:
    static void restore(om::mostream& s, bool on) {
        if (on) {
            s.enable();
        } else {
            s.disable();
        }
    }
    bool err_, log_, out_;
};

/// Records vertices and faces in the order a reader delivers them; ignores every attribute.
class Collector final : public omio::BaseImporter {
public:
    explicit Collector(RawMesh& out) : out_(out) { out_.face_offsets.assign(1, 0); }

    om::VertexHandle add_vertex(const om::Vec3f& p) override {
        out_.positions.push_back({p[0], p[1], p[2]});
        return om::VertexHandle(static_cast<int>(out_.positions.size() - 1));
    }
    om::VertexHandle add_vertex() override { return add_vertex(om::Vec3f(0, 0, 0)); }
    om::HalfedgeHandle add_edge(om::VertexHandle, om::VertexHandle) override {
        return om::HalfedgeHandle();
    }
    om::FaceHandle add_face(const VHandles& vs) override {
        for (const om::VertexHandle& v : vs) {
            out_.face_indices.push_back(v.idx());
        }
        out_.face_offsets.push_back(out_.face_indices.size());
        return om::FaceHandle(static_cast<int>(out_.face_offsets.size() - 2));
    }
    om::FaceHandle add_face(om::HalfedgeHandle) override { return om::FaceHandle(); }
    void add_face_texcoords(om::FaceHandle,
                            om::VertexHandle,
                            const std::vector<om::Vec2f>&) override {}
    void add_face_texcoords(om::FaceHandle,
                            om::VertexHandle,
                            const std::vector<om::Vec3f>&) override {}
    void set_face_texindex(om::FaceHandle, int) override {}
    void set_point(om::VertexHandle v, const om::Vec3f& p) override {
        if (v.is_valid() && static_cast<std::size_t>(v.idx()) < out_.positions.size()) {
            out_.positions[static_cast<std::size_t>(v.idx())] = {p[0], p[1], p[2]};
        }
    }
    void set_halfedge(om::VertexHandle, om::HalfedgeHandle) override {}
    void set_normal(om::VertexHandle, const om::Vec3f&) override {}
    void set_normal(om::VertexHandle, const om::Vec3d&) override {}
    void set_color(om::VertexHandle, const om::Vec3uc&) override {}
    void set_color(om::VertexHandle, const om::Vec4uc&) override {}
    void set_color(om::VertexHandle, const om::Vec3f&) override {}
    void set_color(om::VertexHandle, const om::Vec4f&) override {}
    void set_texcoord(om::VertexHandle, const om::Vec2f&) override {}
    void set_status(om::VertexHandle, const om::Attributes::StatusInfo&) override {}
    void set_next(om::HalfedgeHandle, om::HalfedgeHandle) override {}
    void set_face(om::HalfedgeHandle, om::FaceHandle) override {}
    void request_face_texcoords2D() override {}
    void set_texcoord(om::HalfedgeHandle, const om::Vec2f&) override {}
    void set_texcoord(om::VertexHandle, const om::Vec3f&) override {}
    void set_texcoord(om::HalfedgeHandle, const om::Vec3f&) override {}
    void set_status(om::HalfedgeHandle, const om::Attributes::StatusInfo&) override {}
    void set_color(om::EdgeHandle, const om::Vec3uc&) override {}
    void set_color(om::EdgeHandle, const om::Vec4uc&) override {}
    void set_color(om::EdgeHandle, const om::Vec3f&) override {}
    void set_color(om::EdgeHandle, const om::Vec4f&) override {}
    void set_status(om::EdgeHandle, const om::Attributes::StatusInfo&) override {}
    void set_normal(om::FaceHandle, const om::Vec3f&) override {}
    void set_normal(om::FaceHandle, const om::Vec3d&) override {}
    void set_color(om::FaceHandle, const om::Vec3uc&) override {}
    void set_color(om::FaceHandle, const om::Vec4uc&) override {}
    void set_color(om::FaceHandle, const om::Vec3f&) override {}
    void set_color(om::FaceHandle, const om::Vec4f&) override {}
    void set_status(om::FaceHandle, const om::Attributes::StatusInfo&) override {}
    void add_texture_information(int, std::string) override {}
    om::BaseKernel* kernel() override { return &kernel_; }
    size_t n_vertices() const override { return out_.positions.size(); }
    size_t n_faces() const override { return out_.face_offsets.size() - 1; }
    size_t n_edges() const override { return 0; }

private:
    RawMesh& out_;
    om::BaseKernel kernel_;  ///< empty: readers look for custom properties here and find none
};

/// Presents a TriangleMesh to OpenMesh's writers: positions and triangles only, in our order.
class Presenter final : public omio::BaseExporter {
public:
    explicit Presenter(const TriangleMesh& m) : m_(m) {}

    om::Vec3f point(om::VertexHandle v) const override {
        const Vec3f& p = m_.positions[static_cast<std::size_t>(v.idx())];
        return {p.x, p.y, p.z};
    }
    om::Vec3d pointd(om::VertexHandle v) const override {
        const Vec3f& p = m_.positions[static_cast<std::size_t>(v.idx())];
        return {p.x, p.y, p.z};
    }
    bool is_point_double() const override { return false; }
    om::Vec3f normal(om::VertexHandle) const override { return {0, 0, 0}; }
    om::Vec3d normald(om::VertexHandle) const override { return {0, 0, 0}; }
    bool is_normal_double() const override { return false; }
    om::Vec3uc color(om::VertexHandle) const override { return {0, 0, 0}; }
    om::Vec4uc colorA(om::VertexHandle) const override { return {0, 0, 0, 0}; }
    om::Vec3ui colori(om::VertexHandle) const override { return {0, 0, 0}; }
    om::Vec4ui colorAi(om::VertexHandle) const override { return {0, 0, 0, 0}; }
    om::Vec3f colorf(om::VertexHandle) const override { return {0, 0, 0}; }
    om::Vec4f colorAf(om::VertexHandle) const override { return {0, 0, 0, 0}; }
    om::Vec2f texcoord(om::VertexHandle) const override { return {0, 0}; }
    om::Vec2f texcoord(om::HalfedgeHandle) const override { return {0, 0}; }
    om::Attributes::StatusInfo status(om::VertexHandle) const override { return {}; }
    unsigned int get_vhandles(om::FaceHandle f, std::vector<om::VertexHandle>& vs) const override {
        const auto& t = m_.triangles[static_cast<std::size_t>(f.idx())];
        vs.clear();
        for (const std::uint32_t i : t) {
            vs.emplace_back(static_cast<int>(i));
        }
        return 3;
    }
    om::HalfedgeHandle getHeh(om::FaceHandle, om::VertexHandle) const override {
        return om::HalfedgeHandle();
    }
    unsigned int get_face_texcoords(std::vector<om::Vec2f>&) const override { return 0; }
    om::Vec3f normal(om::FaceHandle f) const override {
        const auto c = m_.corners(static_cast<std::size_t>(f.idx()));
        const Vec3f n = cross(c[1] - c[0], c[2] - c[0]);
        const float len = length(n);
        return len > 0 ? om::Vec3f(n.x / len, n.y / len, n.z / len) : om::Vec3f(0, 0, 0);
    }
    om::Vec3d normald(om::FaceHandle f) const override {
        const om::Vec3f n = normal(f);
        return {n[0], n[1], n[2]};
    }
    om::Vec3uc color(om::FaceHandle) const override { return {0, 0, 0}; }
    om::Vec4uc colorA(om::FaceHandle) const override { return {0, 0, 0, 0}; }
    om::Vec3ui colori(om::FaceHandle) const override { return {0, 0, 0}; }
    om::Vec4ui colorAi(om::FaceHandle) const override { return {0, 0, 0, 0}; }
    om::Vec3f colorf(om::FaceHandle) const override { return {0, 0, 0}; }
    om::Vec4f colorAf(om::FaceHandle) const override { return {0, 0, 0, 0}; }
    om::Attributes::StatusInfo status(om::FaceHandle) const override { return {}; }
    om::Vec3uc color(om::EdgeHandle) const override { return {0, 0, 0}; }
    om::Vec4uc colorA(om::EdgeHandle) const override { return {0, 0, 0, 0}; }
    om::Vec3ui colori(om::EdgeHandle) const override { return {0, 0, 0}; }
    om::Vec4ui colorAi(om::EdgeHandle) const override { return {0, 0, 0, 0}; }
    om::Vec3f colorf(om::EdgeHandle) const override { return {0, 0, 0}; }
    om::Vec4f colorAf(om::EdgeHandle) const override { return {0, 0, 0, 0}; }
    om::Attributes::StatusInfo status(om::EdgeHandle) const override { return {}; }
    int get_halfedge_id(om::VertexHandle) override { return -1; }
    int get_halfedge_id(om::FaceHandle) override { return -1; }
    int get_next_halfedge_id(om::HalfedgeHandle) override { return -1; }
    int get_to_vertex_id(om::HalfedgeHandle) override { return -1; }
    int get_face_id(om::HalfedgeHandle) override { return -1; }
    om::Attributes::StatusInfo status(om::HalfedgeHandle) const override { return {}; }
    const om::BaseKernel* kernel() override { return &kernel_; }
    size_t n_vertices() const override { return m_.positions.size(); }
    size_t n_faces() const override { return m_.triangles.size(); }
    size_t n_edges() const override { return 0; }
    bool is_triangle_mesh() const override { return true; }

private:
    const TriangleMesh& m_;
    om::BaseKernel kernel_;  ///< empty: writers look for custom properties here and find none
};

}  // namespace

bool openmesh_read(const std::filesystem::path& path, RawMesh& out) {
    const QuietOpenMesh quiet;
    out = RawMesh{};
    Collector collector(out);
    omio::Options options;
    return omio::IOManager().read(path.string(), collector, options);
}

bool openmesh_write(const TriangleMesh& mesh, const std::filesystem::path& path, bool binary) {
    const QuietOpenMesh quiet;
    Presenter presenter(mesh);
    omio::Options options;
    if (binary) {
        options += omio::Options::Binary;
        options += omio::Options::LSB;
    }
    return omio::IOManager().write(path.string(), presenter, options, 9);
}

}  // namespace rtlab::detail

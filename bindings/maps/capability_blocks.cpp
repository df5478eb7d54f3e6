// CapabilityBlocks: the steps of the block build, with their seeds and results as bytes for a task system.
#include "maps/convert.hpp"
#include "octoreach/capability_blocks.hpp"

namespace octoreach::py_bindings {
namespace {

std::vector<std::string> byte_strings(const py::handle& items, const char* what) {
  if (py::isinstance<py::str>(items) || py::isinstance<py::bytes>(items) || !py::isinstance<py::sequence>(items))
    throw py::type_error(std::string(what) + " must be a list of bytes");
  std::vector<std::string> out;
  for (const py::handle& item : py::reinterpret_borrow<py::sequence>(items)) {
    if (!py::isinstance<py::bytes>(item))
      throw py::type_error(std::string(what) + " must be a list of bytes, got an item of type " +
                           std::string(py::str(py::type::handle_of(item).attr("__name__"))));
    out.push_back(item.cast<std::string>());
  }
  return out;
}

}  // namespace

void wrap_capability_blocks(py::module_& m) {
  py::class_<CapabilityBlocks> cls(m, "CapabilityBlocks",
      "The block build of a capability map (block_size voxels per block edge, default 16): one FK sampling\n"
      "of the whole workspace box, then each block's IK waves, flood fill and retry pass on its own cells,\n"
      "then a merge. A block's result depends on its seeds alone, so blocks built on any machine merge into\n"
      "the bytes CapabilityMap.build gives for the same options (block_size included). Seeds and results are\n"
      "bytes that carry a fingerprint of the plan; every machine must run the same octoreach build.");
  cls.def(py::init([](const Robot& robot, const py::object& arm, const py::object& options, const py::kwargs& kw) {
        py::object axis = kw.contains("approach_axis") ? kw.attr("pop")("approach_axis") : py::none();
        CapabilityMapOptions o = options_from<CapabilityMapOptions>(options, kw, "CapabilityBlocks");
        Arm a = arm_from(robot, arm, axis);
        py::gil_scoped_release release;
        return CapabilityBlocks(robot, a, o);
      }), py::arg("robot"), py::arg("arm"), py::arg("options") = py::none(),
      "Plans the block build of an arm (name, Arm or (base, tip[, approach_axis]) tuple); keywords set\n"
      "CapabilityMapOptions fields (block_size 0 becomes 16).")
      .def_property_readonly("count", &CapabilityBlocks::count, "Number of blocks.")
      .def_property_readonly("block_size", &CapabilityBlocks::block_size, "Voxels per block edge.")
      .def_property_readonly("options", &CapabilityBlocks::options, "Options of the map built (block_size set).")
      .def_property_readonly("fingerprint", &CapabilityBlocks::fingerprint,
                             "Fingerprint of the plan (robot model, options, reference posture, box).")
      .def("sample", [](const CapabilityBlocks& b, const py::object& progress) {
        ProgressCallback cb = progress_arg(progress, "FK sampling");
        std::vector<std::string> seeds;
        {
          py::gil_scoped_release release;
          seeds = b.sample(cb);
        }
        py::list out;
        for (const std::string& s : seeds) out.append(py::bytes(s));
        return out;
      }, py::arg("progress") = false, "Step 1: the FK sampling of the whole box as one seed list (bytes) per block.")
      .def_static("seed_count", [](const py::bytes& seeds) { return CapabilityBlocks::seed_count(seeds.cast<std::string>()); },
                  py::arg("seeds"), "Seeds in a seed list (the work of its block).")
      .def("build_block", [](const CapabilityBlocks& b, std::size_t block, const py::bytes& seeds, const py::object& progress) {
        std::string s = seeds.cast<std::string>(), out;
        ProgressCallback cb = progress_arg(progress, "capability block");
        {
          py::gil_scoped_release release;
          out = b.build_block(block, s, cb);
        }
        return py::bytes(out);
      }, py::arg("block"), py::arg("seeds"), py::arg("progress") = false,
      "Step 2: block `block` from its seed list; its reachable cells and solutions (bytes).")
      .def("merge", [](const CapabilityBlocks& b, const py::object& results) {
        std::vector<std::string> r = byte_strings(results, "results");
        py::gil_scoped_release release;
        return b.merge(r);
      }, py::arg("results"), "Step 3: the CapabilityMap from every block's result, in block order.")
      .def("build", [](const CapabilityBlocks& b, const py::object& progress) {
        ProgressCallback cb = progress_arg(progress, "capability map");
        py::gil_scoped_release release;
        return b.build(cb);
      }, py::arg("progress") = true, "The three steps in this process (as CapabilityMap.build with block_size).")
      .def("__repr__", [](const CapabilityBlocks& b) {
        return "<octoreach.CapabilityBlocks " + std::to_string(b.count()) + " blocks of " +
               std::to_string(b.block_size()) + " voxels>";
      });
}

}  // namespace octoreach::py_bindings

// The GPU half of the Slang and HLSL consumers: runs one compiled consumer kernel on Vulkan
// (lavapipe here) with the installed package's Vulkan runner (openpbr::vulkan_runner) and
// compares its results with the C++ build on the same queries (openpbr_consumer.h).
//
//   gpu_consumer <name> <kernel.spv> <table directory>
//
// Bindings of both kernels (set 0; HLSL registers in brackets), as the README's "Integrating"
// section lists them: 0 [t0] the energy-compensation tables (openpbr_lut.bin), 1 [t1] the fuzz
// table (openpbr_fuzz_ltc.bin), 2 [t2] queries, 3 [t3] packed materials, 4 [t4] the query
// count, 5 [u5] results. Exit status 0 when the kernel agrees with the C++ build.
#include <cstdio>
#include <exception>
#include <string>

#include "host/gpu/vulkan_runner.h"
#include "openpbr_consumer.h"

using namespace openpbr_consumer;
namespace host = openpbr::host;

int main(int argc, char** argv)
{
    if (argc != 4)
    {
        std::fprintf(stderr, "usage: %s <name> <kernel.spv> <table directory>\n", argv[0]);
        return 2;
    }
    const std::string name = argv[1];
    const std::string kernel_path = argv[2];
    const std::string table_directory = argv[3];
    try
    {
        std::string error;
        std::optional<host::VulkanContext> context = host::VulkanContext::create(host::VulkanOptions{}, &error);
        if (!context)
        {
            std::fprintf(stderr, "%s: no Vulkan device: %s\n", name.c_str(), error.c_str());
            return 1;
        }
        const std::vector<OpenPBR_ResolvedInputs> materials = make_materials();
        const std::vector<float> queries = make_queries(1024, materials.size());
        const std::size_t query_count = queries.size() / query_floats;

        std::vector<std::byte> lut =
            host::to_bytes(read_table(table_directory + "/openpbr_lut.bin", OPENPBR_LUT_TOTAL_COUNT));
        std::vector<std::byte> fuzz_ltc =
            host::to_bytes(read_table(table_directory + "/openpbr_fuzz_ltc.bin", OPENPBR_FUZZ_LTC_TOTAL_COUNT));
        std::vector<std::byte> query_bytes = host::to_bytes(queries);
        std::vector<std::byte> material_bytes = host::to_bytes(pack_materials(materials));
        std::vector<std::byte> parameters = host::to_bytes(std::vector<std::uint32_t>{std::uint32_t(query_count), 0, 0, 0});
        std::vector<std::byte> result_bytes(query_count * result_floats * sizeof(float));
        const std::vector<host::BufferBinding> buffers = {{0, &lut, false},         {1, &fuzz_ltc, false},
                                                          {2, &query_bytes, false}, {3, &material_bytes, false},
                                                          {4, &parameters, false},  {5, &result_bytes, true}};
        host::ComputePipelineDescription description;
        description.spirv_words = host::load_spirv_file(kernel_path);
        description.entry_point = "main";
        description.bindings = host::binding_layouts_of(buffers);
        host::ComputePipeline pipeline(*context, description);
        host::run(pipeline, buffers, std::uint32_t((query_count + 63) / 64));

        std::printf("%s on %s\n", name.c_str(), context->device_name().c_str());
        const bool agree =
            compare_with_cpu(name.c_str(), host::from_bytes<float>(result_bytes), shade_all_on_cpu(materials, queries));
        return agree ? 0 : 1;
    }
    catch (const std::exception& failure)
    {
        std::fprintf(stderr, "%s: %s\n", name.c_str(), failure.what());
        return 1;
    }
}

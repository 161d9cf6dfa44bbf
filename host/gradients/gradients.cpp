// gradients.cpp - the C++ face of Slang's C++ output of targets/autodiff/gradients.slang (see
// gradients.h). This translation unit includes that generated file (OPENPBR_GRADIENT_CODE, set by
// CMake), whose types and functions live in the global namespace with Slang's names (a `_0` suffix
// on each export), and converts between them and the plain arrays of gradients.h.
#include "host/gradients/gradients.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include <pthread.h>

#include OPENPBR_GRADIENT_CODE

namespace openpbr::host::gradients {

namespace {

using GeneratedMaterial = FixedArray<float, material_floats>;
using GeneratedValue = FixedArray<float, value_floats>;
using GeneratedDirection = Vector<float, 3>;

static_assert(sizeof(GeneratedMaterial) == sizeof(MaterialRecord), "the packed record's size");
static_assert(sizeof(GeneratedValue) == sizeof(ValueRecord), "the value record's size");

GeneratedMaterial to_generated(const MaterialRecord& record)
{
    GeneratedMaterial generated;
    std::memcpy(&generated, record.data(), sizeof generated);
    return generated;
}

GeneratedValue to_generated(const ValueRecord& record)
{
    GeneratedValue generated;
    std::memcpy(&generated, record.data(), sizeof generated);
    return generated;
}

GeneratedDirection to_generated(const Direction& direction) { return {direction[0], direction[1], direction[2]}; }

template <typename Record, typename Generated> Record from_generated(const Generated& generated)
{
    static_assert(sizeof(Generated) == sizeof(Record), "record sizes");
    Record record;
    std::memcpy(record.data(), &generated, sizeof generated);
    return record;
}

Direction from_generated_direction(const GeneratedDirection& direction) { return {direction.x, direction.y, direction.z}; }

// The queries of one view: prepare, each light's value, its cotangent and the reverse pass of eval
// and pdf summed into the prepared BSDF's differential, then prepare's reverse pass.
void view_reverse(GeneratedMaterial& material, const ViewQueries& view, std::size_t first_query,
                  const CotangentFunction& cotangent_of, std::vector<ValueRecord>* values, MaterialRecord& gradient)
{
    GeneratedDirection generated_view = to_generated(view.view);
    OpenPBR_PreparedBsdf_0 bsdf;
    openpbr_gradient_prepare_0(&material, &generated_view, &bsdf);
    OpenPBR_PreparedBsdf_Differential_0 d_bsdf;
    openpbr_gradient_prepared_zero_0(&d_bsdf);
    for (std::size_t light = 0; light < view.lights.size(); ++light)
    {
        GeneratedDirection generated_light = to_generated(view.lights[light]);
        GeneratedValue value;
        openpbr_gradient_prepared_query_value_0(&bsdf, &generated_light, &value);
        const ValueRecord record = from_generated<ValueRecord>(value);
        if (values != nullptr)
        {
            (*values)[first_query + light] = record;
        }
        GeneratedValue cotangent = to_generated(cotangent_of(first_query + light, record));
        openpbr_gradient_prepared_query_reverse_0(&bsdf, &generated_light, &cotangent, &d_bsdf);
    }
    GeneratedMaterial d_material;
    GeneratedDirection d_view;
    openpbr_gradient_prepare_reverse_0(&material, &generated_view, &d_bsdf, &d_material, &d_view);
    const MaterialRecord view_gradient = from_generated<MaterialRecord>(d_material);
    for (std::size_t slot = 0; slot < material_floats; ++slot)
    {
        gradient[slot] += view_gradient[slot];
    }
}

constexpr std::size_t large_stack_bytes = std::size_t(64) << 20;  // 64 MiB, see gradients.h

extern "C" void* run_work(void* argument)
{
    auto* work = static_cast<std::function<void()>*>(argument);
    (*work)();
    return nullptr;
}

// Starts `work` on a new thread with the large stack; returns its handle.
pthread_t start_large_stack_thread(std::function<void()>* work)
{
    pthread_attr_t attributes;
    pthread_attr_init(&attributes);
    pthread_attr_setstacksize(&attributes, large_stack_bytes);
    pthread_t thread;
    const int status = pthread_create(&thread, &attributes, run_work, work);
    pthread_attr_destroy(&attributes);
    if (status != 0)
    {
        throw std::runtime_error("gradients: cannot start a thread with a " + std::to_string(large_stack_bytes >> 20) +
                                 " MiB stack (pthread_create: " + std::to_string(status) + ")");
    }
    return thread;
}

}  // namespace

void run_on_large_stack(const std::function<void()>& work)
{
    std::exception_ptr failure;
    std::function<void()> guarded = [&]() {
        try
        {
            work();
        }
        catch (...)
        {
            failure = std::current_exception();
        }
    };
    pthread_join(start_large_stack_thread(&guarded), nullptr);
    if (failure)
    {
        std::rethrow_exception(failure);
    }
}

namespace {

// The plain value of one query, on the calling thread (which must have the large stack).
ValueRecord generated_query_value(GeneratedMaterial& material, GeneratedDirection& view, GeneratedDirection& light)
{
    GeneratedValue value;
    openpbr_gradient_query_value_0(&material, &view, &light, &value);
    return from_generated<ValueRecord>(value);
}

}  // namespace

ValueRecord query_value(const MaterialRecord& material, const Direction& view, const Direction& light)
{
    ValueRecord result{};
    run_on_large_stack([&]() {
        GeneratedMaterial generated_material = to_generated(material);
        GeneratedDirection generated_view = to_generated(view);
        GeneratedDirection generated_light = to_generated(light);
        result = generated_query_value(generated_material, generated_view, generated_light);
    });
    return result;
}

ValueRecord query_reverse(const MaterialRecord& material, const Direction& view, const Direction& light,
                          const ValueRecord& cotangent, QueryGradient& gradient)
{
    ValueRecord result{};
    run_on_large_stack([&]() {
        GeneratedMaterial generated_material = to_generated(material);
        GeneratedDirection generated_view = to_generated(view);
        GeneratedDirection generated_light = to_generated(light);
        result = generated_query_value(generated_material, generated_view, generated_light);
        GeneratedValue generated_cotangent = to_generated(cotangent);
        GeneratedMaterial d_material;
        GeneratedDirection d_view;
        GeneratedDirection d_light;
        openpbr_gradient_query_reverse_0(&generated_material, &generated_view, &generated_light, &generated_cotangent,
                                         &d_material, &d_view, &d_light);
        gradient.material = from_generated<MaterialRecord>(d_material);
        gradient.view = from_generated_direction(d_view);
        gradient.light = from_generated_direction(d_light);
    });
    return result;
}

ValueRecord query_forward(const MaterialRecord& material, const MaterialRecord& material_tangent, const Direction& view,
                          const Direction& view_tangent, const Direction& light, const Direction& light_tangent,
                          ValueRecord& derivative)
{
    ValueRecord result{};
    run_on_large_stack([&]() {
        GeneratedMaterial generated_material = to_generated(material);
        GeneratedMaterial generated_tangent = to_generated(material_tangent);
        GeneratedDirection generated_view = to_generated(view);
        GeneratedDirection generated_view_tangent = to_generated(view_tangent);
        GeneratedDirection generated_light = to_generated(light);
        GeneratedDirection generated_light_tangent = to_generated(light_tangent);
        GeneratedValue value;
        GeneratedValue generated_derivative;
        openpbr_gradient_query_forward_0(&generated_material, &generated_tangent, &generated_view, &generated_view_tangent,
                                         &generated_light, &generated_light_tangent, &value, &generated_derivative);
        result = from_generated<ValueRecord>(value);
        derivative = from_generated<ValueRecord>(generated_derivative);
    });
    return result;
}

MaterialRecord batch_reverse(const MaterialRecord& material, const std::vector<ViewQueries>& views,
                             const CotangentFunction& cotangent_of, std::vector<ValueRecord>* values, unsigned threads)
{
    std::vector<std::size_t> first_query(views.size() + 1, 0);
    for (std::size_t view = 0; view < views.size(); ++view)
    {
        first_query[view + 1] = first_query[view] + views[view].lights.size();
    }
    if (values != nullptr)
    {
        values->assign(first_query.back(), ValueRecord{});
    }
    const unsigned worker_count = std::max(
        1u, std::min(threads == 0 ? std::thread::hardware_concurrency() : threads, static_cast<unsigned>(views.size())));
    // Worker w takes views w, w + W, ... and sums their gradients; the sums are added in worker
    // order, so the result does not depend on the scheduling, only on the worker count.
    std::vector<MaterialRecord> sums(worker_count, MaterialRecord{});
    std::vector<std::exception_ptr> failures(worker_count);
    std::vector<std::function<void()>> work(worker_count);
    std::vector<pthread_t> workers;
    for (unsigned worker = 0; worker < worker_count; ++worker)
    {
        work[worker] = [&, worker]() {
            try
            {
                GeneratedMaterial generated_material = to_generated(material);
                for (std::size_t view = worker; view < views.size(); view += worker_count)
                {
                    view_reverse(generated_material, views[view], first_query[view], cotangent_of, values, sums[worker]);
                }
            }
            catch (...)
            {
                failures[worker] = std::current_exception();
            }
        };
        workers.push_back(start_large_stack_thread(&work[worker]));
    }
    for (pthread_t worker : workers)
    {
        pthread_join(worker, nullptr);
    }
    for (const std::exception_ptr& failure : failures)
    {
        if (failure)
        {
            std::rethrow_exception(failure);
        }
    }
    MaterialRecord gradient{};
    for (const MaterialRecord& sum : sums)
    {
        for (std::size_t slot = 0; slot < material_floats; ++slot)
        {
            gradient[slot] += sum[slot];
        }
    }
    return gradient;
}

}  // namespace openpbr::host::gradients

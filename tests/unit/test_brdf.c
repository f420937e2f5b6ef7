/* The BRDF conventions of common/brdf.h and their importance sampling
 * (common/brdf_sampling.c): energy, reciprocity, a sampling density
 * that integrates to one and matches the directions drawn. */
#include <math.h>

#include "brdf_sampling.h"
#include "random.h"
#include "tap.h"

static const double PI = 3.14159265358979323846;
static const gb_vec3 UP = {0, 0, 1};

static gb_vec3 direction_at(double theta_degrees, double phi_degrees)
{
    double t = theta_degrees * PI / 180, p = phi_degrees * PI / 180;
    return gb_vec3_make((float)(sin(t) * cos(p)), (float)(sin(t) * sin(p)), (float)cos(t));
}

static gb_vec3 uniform_hemisphere(gb_random *rng)
{
    float z = gb_random_float(rng), phi = 2 * (float)PI * gb_random_float(rng);
    float r = sqrtf(fmaxf(0.0f, 1 - z * z));
    return gb_vec3_make(r * cosf(phi), r * sinf(phi), z);
}

/* Directional albedo of the green channel, integrated with uniform
 * directions (density 1 / 2 pi). */
static double albedo_uniform(const gb_brdf *brdf, gb_vec3 wo, int samples)
{
    gb_random rng = gb_random_make(3, 0);
    double sum = 0;
    for (int i = 0; i < samples; ++i) {
        gb_vec3 wi = uniform_hemisphere(&rng);
        sum += gb_brdf_eval_vectors(brdf, UP, wo, wi).y * wi.z * 2 * PI;
    }
    return sum / samples;
}

/* The same, as the mean weight of importance-sampled directions. */
static double albedo_sampled(const gb_brdf *brdf, gb_vec3 wo, int samples)
{
    gb_random rng = gb_random_make(4, 0);
    double sum = 0;
    for (int i = 0; i < samples; ++i) {
        gb_brdf_sample s;
        float a = gb_random_float(&rng), b = gb_random_float(&rng), c = gb_random_float(&rng);
        if (gb_brdf_sample_direction(brdf, UP, wo, a, b, c, &s))
            sum += s.weight.y;
    }
    return sum / samples;
}

static double pdf_integral(const gb_brdf *brdf, gb_vec3 wo, int samples)
{
    gb_random rng = gb_random_make(5, 0);
    double sum = 0;
    for (int i = 0; i < samples; ++i)
        sum += gb_brdf_pdf(brdf, UP, wo, uniform_hemisphere(&rng)) * 2 * PI;
    return sum / samples;
}

static void test_phong_energy(void)
{
    gb_brdf glossy = {{0, 0, 0}, {1, 1, 1}, 20};
    CHECK_NEAR(albedo_uniform(&glossy, UP, 400000), 1.0, 0.02,
               "normalised Phong (Ks 1, Ns 20) reflects all light at normal incidence");
    int passive = 1;
    for (double theta = 10; theta < 90; theta += 20)
        passive &= albedo_uniform(&glossy, direction_at(theta, 0), 200000) <= 1.01;
    CHECK(passive, "normalised Phong reflects at most all light at 10..70 degrees");
    gb_brdf diffuse = {{0.5f, 0.5f, 0.5f}, {0, 0, 0}, 0};
    CHECK_NEAR(albedo_uniform(&diffuse, direction_at(40, 30), 200000), 0.5, 0.01,
               "Lambert: albedo Kd");
}

static void test_reciprocity(void)
{
    gb_brdf brdf = {{0.3f, 0.4f, 0.5f}, {0.2f, 0.3f, 0.4f}, 35};
    double worst = 0;
    for (double a = 5; a < 90; a += 17)
        for (double b = 3; b < 90; b += 19) {
            gb_vec3 wo = direction_at(a, 10), wi = direction_at(b, 200 - a);
            gb_vec3 f1 = gb_brdf_eval_vectors(&brdf, UP, wo, wi);
            gb_vec3 f2 = gb_brdf_eval_vectors(&brdf, UP, wi, wo);
            worst = fmax(worst, fabs(f1.z - f2.z) / fmax(f1.z, 1e-6));
        }
    CHECK(worst < 1e-5, "f(wo, wi) = f(wi, wo)");
    gb_vec3 below = gb_vec3_make(0.3f, 0, -0.95f);
    CHECK(gb_vec3_is_zero(gb_brdf_eval_vectors(&brdf, UP, direction_at(30, 0), below)),
          "no reflection from below the surface");
}

static void test_sampling(void)
{
    const gb_brdf brdfs[3] = {
        {{0.6f, 0.6f, 0.6f}, {0, 0, 0}, 0},
        {{0.2f, 0.3f, 0.2f}, {0.5f, 0.4f, 0.3f}, 10},
        {{0.05f, 0.05f, 0.05f}, {0.9f, 0.9f, 0.9f}, 200},
    };
    const double angles[3] = {0, 35, 70};
    double worst_pdf = 0, worst_albedo = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            gb_vec3 wo = direction_at(angles[j], 45);
            /* the Phong lobe around the mirror direction loses what falls
             * below the surface at oblique angles (those samples are
             * refused); all of it lies above at normal incidence */
            double pdf = pdf_integral(&brdfs[i], wo, 400000);
            int whole = j == 0 || i == 0;
            worst_pdf = fmax(worst_pdf, whole ? fabs(pdf - 1.0) : fmax(0.0, pdf - 1.0));
            double a = albedo_uniform(&brdfs[i], wo, 400000);
            double b = albedo_sampled(&brdfs[i], wo, 100000);
            worst_albedo = fmax(worst_albedo, fabs(a - b));
        }
    CHECK(worst_pdf < 0.01, "the sampling density integrates to 1 over the hemisphere (at "
          "most 1 where the Phong lobe dips below it), 3 BRDFs x 3 angles");
    CHECK(worst_albedo < 0.02, "sampled weights average to the albedo (3 BRDFs x 3 angles)");
}

static void test_light_conventions(void)
{
    CHECK(gb_spot_falloff(cosf(0.1f), 40, 20) == 1.0f &&
              gb_spot_falloff(cosf(45 * (float)PI / 180), 40, 20) == 0.0f,
          "spot: 1 inside the fall-off angle, 0 outside the cone");
    float middle = 0.5f * (cosf(20 * (float)PI / 180) + cosf(40 * (float)PI / 180));
    float half = gb_spot_falloff(middle, 40, 20);
    CHECK_NEAR(half, 0.5, 1e-5, "spot: smoothstep of the cosines is 1/2 half way");
    CHECK(gb_spot_falloff(cosf(29 * (float)PI / 180), 30, 30) == 1.0f,
          "spot: equal angles give a hard edge");
    CHECK_NEAR(gb_vpl_emission(1.0f), 1 / PI, 1e-7, "VPL: intensity P cos / pi");
    CHECK(gb_vpl_emission(-0.5f) == 0.0f, "VPL: one-sided");
}

int main(void)
{
    test_phong_energy();
    test_reciprocity();
    test_sampling();
    test_light_conventions();
    return tap_done();
}

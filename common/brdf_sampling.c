#include "brdf_sampling.h"

static float luminance(const float c[3])
{
    return gb_vec3_luminance(gb_vec3_load(c));
}

/* Probability of sampling the Phong lobe rather than the diffuse one. */
static float glossy_probability(const gb_brdf *brdf)
{
    float diffuse = luminance(brdf->Kd), glossy = luminance(brdf->Ks);
    return diffuse + glossy > 0.0f ? glossy / (diffuse + glossy) : 0.0f;
}

static gb_vec3 mirror(gb_vec3 n, gb_vec3 wo)
{
    return gb_vec3_sub(gb_vec3_scale(n, 2.0f * gb_vec3_dot(n, wo)), wo);
}

gb_vec3 gb_brdf_eval_vectors(const gb_brdf *brdf, gb_vec3 n, gb_vec3 wo, gb_vec3 wi)
{
    float f[3];
    gb_brdf_eval(brdf, gb_vec3_dot(n, wo), gb_vec3_dot(n, wi), gb_vec3_dot(wo, wi), f);
    return gb_vec3_load(f);
}

/* Density of the Phong lobe sampling: (Ns + 1) / (2 pi) cos^Ns a. */
static float phong_pdf(float Ns, float cos_mirror)
{
    return cos_mirror > 0.0f ? (Ns + 1.0f) / (2.0f * GB_PI) * powf(cos_mirror, Ns) : 0.0f;
}

static int is_glossy(const gb_brdf *brdf)
{
    return brdf->Ks[0] > 0.0f || brdf->Ks[1] > 0.0f || brdf->Ks[2] > 0.0f;
}

float gb_brdf_pdf(const gb_brdf *brdf, gb_vec3 n, gb_vec3 wo, gb_vec3 wi)
{
    float cos_i = gb_vec3_dot(n, wi);
    if (cos_i <= 0.0f || gb_vec3_dot(n, wo) <= 0.0f)
        return 0.0f;
    if (!is_glossy(brdf))
        return cos_i / GB_PI;
    float glossy = glossy_probability(brdf);
    float pdf = (1.0f - glossy) * cos_i / GB_PI;
    if (glossy > 0.0f)
        pdf += glossy * phong_pdf(brdf->Ns, gb_vec3_dot(mirror(n, wo), wi));
    return pdf;
}

/* A direction around axis whose cosine to it has density proportional to
 * cos^exponent: cos = u1^(1 / (exponent + 1)). */
static gb_vec3 sample_power_cosine(gb_vec3 axis, float exponent, float u1, float u2)
{
    float cos_theta = exponent == 1.0f ? sqrtf(u1) : powf(u1, 1.0f / (exponent + 1.0f));
    float sin_theta = sqrtf(fmaxf(0.0f, 1.0f - cos_theta * cos_theta));
    float phi = 2.0f * GB_PI * u2;
    gb_vec3 t, b;
    gb_vec3_frame(axis, &t, &b);
    return gb_vec3_from_frame(t, b, axis, sin_theta * cosf(phi), sin_theta * sinf(phi),
                              cos_theta);
}

/* Lambert alone: cosine-weighted wi, and f cos / pdf = Kd exactly. */
static int sample_diffuse(const gb_brdf *brdf, gb_vec3 n, float u1, float u2,
                          gb_brdf_sample *sample)
{
    gb_vec3 wi = gb_vec3_normalize(sample_power_cosine(n, 1.0f, u1, u2));
    float cos_i = gb_vec3_dot(n, wi);
    if (!(cos_i > 0.0f))
        return 0;
    sample->wi = wi;
    sample->pdf = cos_i / GB_PI;
    sample->weight = gb_vec3_load(brdf->Kd);
    return 1;
}

int gb_brdf_sample_direction(const gb_brdf *brdf, gb_vec3 n, gb_vec3 wo, float u_lobe,
                             float u1, float u2, gb_brdf_sample *sample)
{
    if (!is_glossy(brdf))
        return gb_vec3_dot(n, wo) > 0.0f && luminance(brdf->Kd) > 0.0f &&
               sample_diffuse(brdf, n, u1, u2, sample);
    if (luminance(brdf->Kd) + luminance(brdf->Ks) <= 0.0f || gb_vec3_dot(n, wo) <= 0.0f)
        return 0;
    float glossy = glossy_probability(brdf);
    gb_vec3 wi = u_lobe < glossy ? sample_power_cosine(mirror(n, wo), brdf->Ns, u1, u2)
                                 : sample_power_cosine(n, 1.0f, u1, u2);
    wi = gb_vec3_normalize(wi);
    float cos_i = gb_vec3_dot(n, wi);
    float pdf = gb_brdf_pdf(brdf, n, wo, wi);
    if (cos_i <= 0.0f || !(pdf > 0.0f))
        return 0;
    sample->wi = wi;
    sample->pdf = pdf;
    sample->weight = gb_vec3_scale(gb_brdf_eval_vectors(brdf, n, wo, wi), cos_i / pdf);
    return 1;
}

// spot_falloff(cos_angle, cone, falloff): the GLSL twin of gb_spot_falloff
// (common/brdf.h), a spot light's smooth fall-off between its half-angles
// (degrees). Needs PI.
float spot_falloff(float cos_angle, float cone_angle_degrees,
                   float falloff_angle_degrees) {
    float cos_cone = cos(cone_angle_degrees * (PI / 180.0));
    float cos_falloff = cos(falloff_angle_degrees * (PI / 180.0));
    if (cos_angle <= cos_cone)
        return 0.0;
    if (cos_angle >= cos_falloff || cos_falloff <= cos_cone)
        return 1.0;
    float t = (cos_angle - cos_cone) / (cos_falloff - cos_cone);
    return t * t * (3.0 - 2.0 * t);
}

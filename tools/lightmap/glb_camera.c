/* glb_camera.c — the scene's camera as a glTF camera node (glb_camera.h). */
#include "glb_camera.h"

#include <math.h>

#include "camera.h"

/* The unit quaternion (x, y, z, w) of the rotation whose matrix has columns
 * c0, c1, c2 (orthonormal, right-handed): Shepperd's method, the largest
 * of the four candidates for precision. */
static void quaternion_of(gb_vec3 c0, gb_vec3 c1, gb_vec3 c2, double q[4])
{
    double m[3][3] = {{c0.x, c1.x, c2.x}, {c0.y, c1.y, c2.y}, {c0.z, c1.z, c2.z}};
    double trace = m[0][0] + m[1][1] + m[2][2];
    if (trace > 0.0) {
        double s = 2.0 * sqrt(1.0 + trace);
        q[0] = (m[2][1] - m[1][2]) / s, q[1] = (m[0][2] - m[2][0]) / s;
        q[2] = (m[1][0] - m[0][1]) / s, q[3] = 0.25 * s;
    } else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
        double s = 2.0 * sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]);
        q[0] = 0.25 * s, q[1] = (m[0][1] + m[1][0]) / s;
        q[2] = (m[0][2] + m[2][0]) / s, q[3] = (m[2][1] - m[1][2]) / s;
    } else if (m[1][1] > m[2][2]) {
        double s = 2.0 * sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]);
        q[0] = (m[0][1] + m[1][0]) / s, q[1] = 0.25 * s;
        q[2] = (m[1][2] + m[2][1]) / s, q[3] = (m[0][2] - m[2][0]) / s;
    } else {
        double s = 2.0 * sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]);
        q[0] = (m[0][2] + m[2][0]) / s, q[1] = (m[1][2] + m[2][1]) / s;
        q[2] = 0.25 * s, q[3] = (m[1][0] - m[0][1]) / s;
    }
    double length = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (int k = 0; k < 4; ++k)
        q[k] /= length;
}

static double diagonal(const gb_scene *scene)
{
    double sum = 0.0;
    for (int k = 0; k < 3; ++k)
        sum += ((double)scene->bounds_max[k] - scene->bounds_min[k]) *
               ((double)scene->bounds_max[k] - scene->bounds_min[k]);
    return sqrt(sum);
}

int gb_glb_print_camera(const gb_scene *scene, gb_byte_buffer *nodes, gb_byte_buffer *cameras)
{
    const gb_camera *camera = &scene->cameras[0];
    gb_camera_frame frame;
    if (scene->camera_count == 0 ||
        gb_camera_frame_make(camera, camera->width, camera->height, &frame, NULL) != GB_OK)
        return 0;
    double q[4];
    quaternion_of(frame.right, frame.up, gb_vec3_negate(frame.forward), q);
    gb_byte_buffer_printf(nodes, ",{\"camera\":0,\"name\":\"camera\",\"translation\":"
                          "[%.9g,%.9g,%.9g],\"rotation\":[%.9g,%.9g,%.9g,%.9g]}",
                          (double)frame.position.x, (double)frame.position.y,
                          (double)frame.position.z, q[0], q[1], q[2], q[3]);
    double near = diagonal(scene) > 0.0 ? 1e-4 * diagonal(scene) : 1e-3;
    gb_byte_buffer_printf(cameras, "[{\"type\":\"perspective\",\"name\":\"camera\","
                          "\"perspective\":{\"yfov\":%.9g,\"aspectRatio\":%.9g,\"znear\":%.9g}}]",
                          (double)camera->fov_y * 3.14159265358979323846 / 180.0,
                          (double)camera->width / camera->height, near);
    return 1;
}

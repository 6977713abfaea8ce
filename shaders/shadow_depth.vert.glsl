#version 450 core
/* Shadow maps, first step (SSDO thesis §2.1, §5.1): the scene from the light. The one raster pass
 * besides the G-buffer: a shadow map is not screen-space, it needs the triangles seen from
 * somewhere else. Reuses the G-buffer's vertex arrays (attribute 0 = world position). */
#define OB_SHADOW_DEPTH_PASS 1
#include "shadow_params.h"

layout(location = 0) in vec3 in_position;

#ifdef OB_SHADOW_DISTANCE
out vec3 v_world;
#endif

void main()
{
#ifdef OB_SHADOW_DISTANCE
    v_world = in_position;
#endif
    gl_Position = shd.view_proj * vec4(in_position, 1.0);
}

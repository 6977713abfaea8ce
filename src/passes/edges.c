/* Adaptive sample counts: the edge pre-pass of SSDO thesis §4.1. Shader: shaders/edges.glsl. */
#include "passes/passes.h"
#include "resample_params.h"

/* A block is an edge (3x samples) when neighbours differ by 5% in depth or by ~25 degrees in
 * normal (1 - cos 25 = 0.094); a third of that gives 2x. Planes seen at a grazing angle change
 * depth by well under 5% per pixel at these resolutions, so they stay at 1x. */
#define EDGE_DEPTH_STEP 0.05f
#define EDGE_NORMAL_TURN 0.094f

ob_error ob_edges_init(ob_compute_pass *p)
{
    return ob_compute_pass_init(p, "edges.glsl", NULL, sizeof(ob_resample_constants));
}

void ob_edges_run(ob_compute_pass *p, const ob_ao_grid *g, GLuint ao_depth, GLuint ao_normal, GLuint multiplier)
{
    ob_resample_constants c;
    ob_resample_fill(&c, g);
    c.edge_depth_step = EDGE_DEPTH_STEP;
    c.edge_normal_turn = EDGE_NORMAL_TURN;
    ob_compute_pass_use(p, &c, sizeof c);
    glBindTextureUnit(OB_UNIT_DEPTH, ao_depth);
    glBindTextureUnit(OB_UNIT_NORMAL, ao_normal);
    glBindImageTexture(OB_IMAGE_UNIT_OUT, multiplier, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    ob_dispatch_2d((g->width + OB_EDGE_BLOCK - 1) / OB_EDGE_BLOCK, (g->height + OB_EDGE_BLOCK - 1) / OB_EDGE_BLOCK,
                   OB_RESAMPLE_GROUP_X, OB_RESAMPLE_GROUP_Y);
}

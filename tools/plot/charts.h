/*
 * charts.h - the four pictures of xgo-plot, each drawn into an SVG at a
 * given top edge, each returning the height it used:
 *   gait     stance (filled bar) and swing per leg over time, from contact1..4
 *   joints   the 12 joint angles over time between their limits (dashed)
 *   path     the world path seen from above, with heading marks
 *   feet     the foot trajectories in the body frame, side and top view
 */
#ifndef XGO_PLOT_CHARTS_H
#define XGO_PLOT_CHARTS_H

#include "record.h"
#include "svg.h"
#include "xgo/profile.h"

#define XGO_PLOT_WIDTH 1100.0 /* page width, px */

double xgo_chart_gait(xgo_svg_t *s, const xgo_rec_t *rec, double top);
double xgo_chart_joints(xgo_svg_t *s, const xgo_rec_t *rec, const xgo_profile_t *p, double top);
/* Sum of the three heights below (fixed, whatever the data). */
double xgo_charts_height(void);
/* path and feet side by side */
double xgo_chart_path_and_feet(xgo_svg_t *s, const xgo_rec_t *rec, double top);

#endif /* XGO_PLOT_CHARTS_H */

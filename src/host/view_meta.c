/*
 * view_meta.c - GET /meta: what the page needs to label and scale what it
 * shows, taken from the core's own tables (register table, action names,
 * profile geometry and ranges) and from --trace's decoder, so the page
 * re-types none of them. Constant for a run. Fields in docs/view.md.
 */
#include "view_meta.h"

#include "decode.h"
#include "view_state.h"

static void xgo_host_view_meta_mm(xgo_host_json_t *w, const char *key, int32_t um)
{
    xgo_host_json_key(w, key);
    xgo_host_json_fixed(w, um, 3, 3);
}

static void xgo_host_view_meta_ranges_array(xgo_host_json_t *w, const char *key,
                                            const xgo_range_t r[3])
{
    unsigned i;
    xgo_host_json_key(w, key);
    xgo_host_json_array_begin(w);
    for (i = 0; i < 3; i++) {
        xgo_host_json_array_begin(w);
        xgo_host_json_fixed(w, r[i].lo, 3, 3);
        xgo_host_json_fixed(w, r[i].hi, 3, 3);
        xgo_host_json_array_end(w);
    }
    xgo_host_json_array_end(w);
}

static void xgo_host_view_meta_registers(xgo_host_json_t *w)
{
    static const char *const k_access[] = {"", "r", "w", "rw"};
    size_t i;
    xgo_host_json_key(w, "registers");
    xgo_host_json_array_begin(w);
    for (i = 0; i < xgo_reg_table_size(); i++) {
        const xgo_reg_desc_t *d = xgo_reg_table_entry(i);
        xgo_host_json_object_begin(w);
        xgo_host_json_key(w, "addr");
        xgo_host_json_uint(w, d->addr);
        xgo_host_json_key(w, "width");
        xgo_host_json_uint(w, d->width);
        xgo_host_json_key(w, "name");
        xgo_host_json_string(w, d->name);
        xgo_host_json_key(w, "access");
        xgo_host_json_string(w, k_access[d->access & 3u]);
        xgo_host_json_object_end(w);
    }
    xgo_host_json_array_end(w);
}

/* Every id with a name (1..XGO_ACTION_LAST, then reset). */
static void xgo_host_view_meta_actions(xgo_host_json_t *w)
{
    unsigned id;
    xgo_host_json_key(w, "actions");
    xgo_host_json_array_begin(w);
    for (id = 1; id <= 255u; id++) {
        const char *name = xgo_action_name((uint8_t)id);
        if (name == NULL) {
            continue;
        }
        xgo_host_json_object_begin(w);
        xgo_host_json_key(w, "id");
        xgo_host_json_uint(w, id);
        xgo_host_json_key(w, "name");
        xgo_host_json_string(w, name);
        xgo_host_json_object_end(w);
    }
    xgo_host_json_array_end(w);
}

/* The words --trace uses for each valid value of an enumerated register. */
static void xgo_host_view_meta_choices(xgo_host_json_t *w, const char *key, uint8_t addr)
{
    const xgo_reg_desc_t *d = xgo_reg_find(addr);
    unsigned v;
    xgo_host_json_key(w, key);
    xgo_host_json_array_begin(w);
    for (v = d != NULL ? d->lo : 1u; d != NULL && v <= d->hi; v++) {
        char word[48];
        xgo_host_decode_value(addr, (uint8_t)v, word, sizeof word);
        xgo_host_json_string(w, word);
    }
    xgo_host_json_array_end(w);
}

static void xgo_host_view_meta_geometry(xgo_host_json_t *w, const xgo_profile_t *p)
{
    xgo_host_json_key(w, "geometry");
    xgo_host_json_object_begin(w);
    xgo_host_view_meta_mm(w, "thigh_mm", p->thigh_um);
    xgo_host_view_meta_mm(w, "shank_mm", p->shank_um);
    xgo_host_json_key(w, "knee_offset_deg");
    xgo_host_json_fixed(w, p->knee_offset_mdeg, 3, 3);
    xgo_host_view_meta_mm(w, "abad_offset_mm", p->abad_offset_um);
    xgo_host_view_meta_mm(w, "hip_x_mm", p->hip_x_um);
    xgo_host_view_meta_mm(w, "hip_y_mm", p->hip_y_um);
    xgo_host_view_meta_mm(w, "length_mm", p->length_um);
    xgo_host_view_meta_mm(w, "width_mm", p->width_um);
    xgo_host_view_meta_mm(w, "stand_height_mm", p->stand_height_um);
    xgo_host_json_object_end(w);
}

/* Full scale of the speed registers, as the core decodes them: a scratch
 * board is told "full speed" (0xFF) and asked what it was commanded. */
static void xgo_host_view_meta_speed_ranges(xgo_host_json_t *w, unsigned model)
{
    static xgo_board_t scratch; /* large: not on the stack */
    static const uint8_t k_full[3] = {0xFF, 0xFF, 0xFF};
    xgo_board_config_t cfg;
    int32_t cmd[3], produced[3];
    xgo_board_default_config(&cfg);
    cfg.model = (xgo_model_t)model;
    xgo_board_init(&scratch, &cfg);
    (void)xgo_board_write(&scratch, XGO_SOURCE_VIEW, XGO_REG_VX, k_full, sizeof k_full);
    xgo_board_velocity(&scratch, cmd, produced);
    xgo_host_view_meta_mm(w, "vx_mm_s", cmd[0]);
    xgo_host_view_meta_mm(w, "vy_mm_s", cmd[1]);
    xgo_host_json_key(w, "vyaw_deg_s");
    xgo_host_json_fixed(w, cmd[2], 3, 3);
}

void xgo_host_view_meta(xgo_host_json_t *w, const xgo_board_t *b, unsigned model)
{
    const xgo_profile_t *p = xgo_profile_get(model);
    unsigned i;
    xgo_host_json_object_begin(w);
    xgo_host_json_key(w, "model");
    xgo_host_json_string(w, p->name);
    xgo_host_json_key(w, "tick_hz");
    xgo_host_json_uint(w, XGO_TICK_HZ);
    xgo_host_view_meta_registers(w);
    xgo_host_view_meta_actions(w);
    xgo_host_json_key(w, "modes");
    xgo_host_json_array_begin(w);
    for (i = 0; i <= XGO_MODE_CALIBRATION; i++) {
        xgo_host_json_string(w, xgo_host_view_mode_name((uint8_t)i));
    }
    xgo_host_json_array_end(w);
    xgo_host_view_meta_choices(w, "gaits", XGO_REG_GAIT_TYPE);
    xgo_host_view_meta_choices(w, "paces", XGO_REG_MOVE_MODE);
    xgo_host_view_joint_limits(w, b, 3);
    xgo_host_view_meta_geometry(w, p);
    xgo_host_json_key(w, "ranges");
    xgo_host_json_object_begin(w);
    xgo_host_view_meta_speed_ranges(w, model);
    xgo_host_view_meta_ranges_array(w, "body_mm", p->body_um);
    xgo_host_view_meta_ranges_array(w, "body_deg", p->body_mdeg);
    xgo_host_json_object_end(w);
    xgo_host_json_object_end(w);
}

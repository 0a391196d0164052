/*
 * view_assets.h - the view page's files, compiled into xgo-emu.
 *
 * The table is generated at build time by cmake/embed_files.cmake from the
 * files in src/host/view/ (build/src/host/view_assets.c): index.html is
 * served at "/", every other file at "/<name>". Nothing is read from disk
 * at run time.
 */
#ifndef XGO_HOST_VIEW_ASSETS_H
#define XGO_HOST_VIEW_ASSETS_H

#include <stddef.h>

typedef struct xgo_host_view_asset_s {
    const char *path;         /* URL path: "/", "/view.js" */
    const char *content_type; /* "text/html; charset=utf-8" */
    const unsigned char *data;
    size_t len;
} xgo_host_view_asset_t;

/* xgo_host_view_asset_count rows, then one all-zero row. */
extern const xgo_host_view_asset_t xgo_host_view_assets[];
extern const size_t xgo_host_view_asset_count;

#endif /* XGO_HOST_VIEW_ASSETS_H */

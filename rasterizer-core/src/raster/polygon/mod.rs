//! Polygons filled by a scanline with an edge table and an active edge table.

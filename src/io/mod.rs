//! Readers and writers for Triangle's file formats (.node, .poly, .ele, .edge, .neigh).

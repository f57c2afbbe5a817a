//! The C ABI (see include/idmesh.h).

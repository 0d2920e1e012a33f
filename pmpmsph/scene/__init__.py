"""Geometry and seeding: body shapes -> particle positions and volumes."""

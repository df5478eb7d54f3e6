"""Limits of the Python layers (room, polygon and job files, names, counts, the viewer), each with the reason
for its value. Every limit is checked before the work or the allocation it bounds, and a value past it is a
ValueError (OSError for a file) that names the value, the limit and this module. The compiled library's
own limits (vertices, image sizes, samples) are checked in C++.
"""
from __future__ import annotations

#: Bytes of a room, polygon or job file, checked with fstat before reading. A 100,000-vertex polygon written
#: as JSON is about 3 MB; 32 MiB leaves ten times that and still parses in about a second.
MAX_DATA_FILE_BYTES = 32 << 20

#: Bytes of a room, polygon or job file read as YAML (a file that is not JSON). PyYAML builds about 400 KB of
#: YAML a second (JSON about a hundred times more): 1 MiB holds a hand-written room of thousands of entries and
#: reads in under three seconds; larger files belong in JSON.
MAX_YAML_BYTES = 1 << 20

#: Nodes of a room, polygon or job file (scalars, lists and mappings) counted with every YAML alias expanded,
#: before the data is built: a 100,000-vertex polygon is 400,000 nodes. A ~1 KB alias bomb expands to
#: billions, which every later walk (checks, messages, the cache key) would pay for.
MAX_DATA_NODES = 2_000_000

#: YAML aliases (``*name``) in one file: repeated entries in a hand-written file are a few dozen.
MAX_DATA_ALIASES = 10_000

#: Nesting of lists and mappings in one file. A room file nests 7 deep (room, surfaces, entry, boxes, box,
#: size, value); past 64 Python's parsers would recurse towards their stack limit.
MAX_DATA_DEPTH = 64

#: Characters of a name (surface, shelf, box, mesh, OctoMap): names become file names (NAME.orsm), and a file
#: name has at most 255 bytes; 200 characters leave room for the extension and a suffix.
MAX_NAME_LENGTH = 200

#: Working surfaces of one room (shelf boards included). Each is one surface-map build with every other
#: obstacle of the room, so the obstacle checks grow with the square of the count.
MAX_SURFACES = 1_000

#: Boards of one shelf: shelves in homes and shops hold a few to a dozen.
MAX_BOARDS = 100

#: Obstacles of one room (boxes, meshes, OctoMaps, a surface's boxes; a table's legs and a shelf's panels
#: count too): every surface-map build checks each candidate base pose against all of them.
MAX_OBSTACLES = 20_000

#: Maps of one build-many job (capability and surface maps together): each is a task and an output file.
MAX_JOB_MAPS = 100_000

#: Base poses the viewer samples and draws (a footprint and an arrow each, and a row in the panel list).
MAX_VIEW_SAMPLES = 10_000

#: Characters of a value quoted in an error message (the start of it, then "..."): a message names the bad
#: value; a whole megabyte list in a one-line error would hide the line.
MAX_SHOWN = 120

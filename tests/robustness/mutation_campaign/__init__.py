"""The modules of the mutation campaign (tests/robustness/campaign.py, its command line):

  xml_mutators    breaks of any XML file (elements, attribute values, parameters)
  map_mutators    OpenDRIVE-specific breaks (lengths, widths, links, junctions, objects)
  layer_mutators  byte-level breaks, and the NGII .dbf/.shp/.shx broken by their layout
  breaking        which file of a case is broken, and how (by its kind)
  sources         per reader (xosc, xodr, ngii, sweep, rig): the folders, files and commands
  runner          one case drawn from (seed, case number), run and judged
"""

"""The numpy core: models, mesh, quadrature, MERL reader.  Never imports textual or rich."""

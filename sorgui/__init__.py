"""sorgui: exact recognition of surfaces of revolution from their implicit equations."""

__version__ = "0.1.0"

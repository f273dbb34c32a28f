"""compiler/arcus"""

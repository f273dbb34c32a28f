"""compiler/mcode"""

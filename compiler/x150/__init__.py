"""compiler/x150"""

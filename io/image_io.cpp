// placeholder replaced by the io helper

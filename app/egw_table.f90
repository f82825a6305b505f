program egw_table_app
   use egw, only: egw_version_string
   implicit none
   print '(a)', "egw-table "//egw_version_string
end program egw_table_app
